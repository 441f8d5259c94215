"""The main job's render-view pictures: the part every picture shares (scalar bar, title, camera, screenshot), and
the features picture."""
import gls_cloud


def save_picture(path, view, lut, bar_title, title, font_size, resolution, dolly=1.0):
    """Shows the scalar bar of `lut` titled `bar_title` and `title` above, fits the camera to the shown data
    (zoomed in by `dolly`), renders and saves a `resolution` screenshot to `path`; removes the title again."""
    from paraview import simple
    bar = simple.GetScalarBar(lut, view)
    bar.Title = bar_title
    bar.ComponentTitle = ''
    text = simple.Text(registrationName='Title', Text=title)
    text_display = simple.Show(text, view)
    text_display.WindowLocation = 'Upper Center'
    text_display.FontSize = font_size
    view.ResetCamera()
    if dolly != 1.0:
        view.GetActiveCamera().Dolly(dolly)
    simple.Render(view)
    simple.SaveScreenshot(path, view, ImageResolution=resolution)
    simple.Delete(text)


def render_features(path, polydata, title):
    """The continuous features on the data: its surface when it has polygons, else every point (drawn as vertex
    cells made for the picture, whatever cells the data has)."""
    from paraview import simple
    from vtkmodules.util.numpy_support import vtk_to_numpy
    surface = gls_cloud.has_surface(polydata)
    shown = polydata if surface else gls_cloud.vertex_cloud(
        vtk_to_numpy(polydata.GetPoints().GetData()),
        {'GLSFeature': vtk_to_numpy(polydata.GetPointData().GetArray('GLSFeature'))})
    source = gls_cloud.producer(shown)
    view = simple.CreateRenderView()
    view.ViewSize = [1200, 900]
    view.OrientationAxesVisibility = 0
    display = simple.Show(source, view)
    if not surface:
        display.SetRepresentationType('Points')
        display.PointSize = 3
    simple.ColorBy(display, ('POINTS', 'GLSFeature'))
    lut = simple.GetColorTransferFunction('GLSFeature')
    lut.ApplyPreset('Inferno (matplotlib)', True)
    lut.RescaleTransferFunction(0.0, 1.0)
    display.SetScalarBarVisibility(view, True)
    save_picture(path, view, lut, 'GLS feature f', title, 22, [1200, 900])
    simple.Delete(view)
    simple.Delete(source)
