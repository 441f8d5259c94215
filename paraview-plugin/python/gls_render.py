"""The main job's render-view pictures: the part every picture shares (scalar bar, title, camera, screenshot)."""


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
