"""The main job's render-view pictures: the part every picture shares (scalar bar, title, camera, screenshot), and
the pictures of a point array (the features, the shape index). A camera chosen from the data: it looks along the
direction in which the points spread least (the view that shows the most of them), from the side most normals face;
a terrain-like cloud (that direction within 30 degrees of Z, and its spread under a fifth of the largest: eigenvalues
1:25) is seen from above, north up.
Clouds above MAX_SHOWN_POINTS are drawn from every k-th point, as the picture's title says."""
import math

import numpy as np

import gls_cloud

# The most points a picture draws: 1M points at point size 2 cover every pixel of the 1200 x 900 picture that the
# cloud covers (a 10M-point cloud's picture: 3.8 s from 2M under Xvfb's software OpenGL, about half from 1M).
MAX_SHOWN_POINTS = 1000000
TERRAIN_SPREAD_RATIO = 0.04     # smallest / largest eigenvalue of the covariance under which a flat cloud...
TERRAIN_AXIS_COSINE = math.cos(math.radians(30.0))  # ...whose thin direction is within 30 degrees of Z is terrain


def camera_from_data(points, normals=None):
    """(direction from the focal point to the camera, view up) for points (n x 3) and their normals (or None)."""
    every = max(1, len(points) // 200000)  # the covariance and the facing from at most about 200,000 points
    sample = np.asarray(points[::every], dtype=float)
    if len(sample) < 3:
        return np.array([0.0, 0.0, 1.0]), np.array([0.0, 1.0, 0.0])
    centred = sample - sample.mean(axis=0)
    values, vectors = np.linalg.eigh(centred.T @ centred / len(sample))
    thin = vectors[:, 0]
    if abs(thin[2]) >= TERRAIN_AXIS_COSINE and values[0] <= TERRAIN_SPREAD_RATIO * values[2]:
        return np.array([0.0, 0.0, 1.0]), np.array([0.0, 1.0, 0.0])
    if normals is not None:
        facing = np.asarray(normals[::every], dtype=float) @ thin
        if np.count_nonzero(facing < 0) > np.count_nonzero(facing > 0):
            thin = -thin
    elif thin[np.argmax(np.abs(thin))] < 0:
        thin = -thin
    up = np.array([0.0, 1.0, 0.0]) if abs(thin[1]) < 0.9 else np.array([0.0, 0.0, 1.0])
    return thin, up


def aim_camera(view, points, normals=None):
    """Points the view's camera at the data (camera_from_data); save_picture then fits the distance."""
    direction, up = camera_from_data(points, normals)
    centre = 0.5 * (np.min(points, axis=0) + np.max(points, axis=0))
    view.CameraFocalPoint = list(map(float, centre))
    view.CameraPosition = list(map(float, centre + direction))
    view.CameraViewUp = list(map(float, up))


# The width of a title's character, as a fraction of its font size (ParaView's default Arial: 0.5 on average; a
# margin for wide letters), which decides where a long title is wrapped.
TITLE_CHARACTER_WIDTH = 0.62


def wrapped_title(title, font_size, width):
    """`title` broken at spaces into lines that fit `width` pixels at `font_size` (a long file name's title is not
    cut at both sides of the picture)."""
    import textwrap
    per_line = max(20, int(width / (TITLE_CHARACTER_WIDTH * font_size)))
    return '\n'.join(textwrap.wrap(title, per_line, break_long_words=True)) or title


def frame_camera(view, points):
    """aim_camera, then the camera's distance set from the points' bounding sphere and the view angle (what
    ResetCamera does, without rendering)."""
    if len(points) == 0:
        return
    aim_camera(view, points)
    centre = np.asarray(view.CameraFocalPoint, dtype=float)
    direction = np.asarray(view.CameraPosition, dtype=float) - centre
    radius = max(0.5 * float(np.linalg.norm(np.max(points, axis=0) - np.min(points, axis=0))), 1e-12 * (1.0 + float(
        np.abs(centre).max())))
    distance = radius / math.sin(math.radians(0.5 * float(view.CameraViewAngle)))
    view.CameraPosition = list(map(float, centre + distance * direction / np.linalg.norm(direction)))
    view.CameraParallelScale = radius


def save_picture(path, view, lut, bar_title, title, font_size, resolution, dolly=1.0):
    """Shows the scalar bar of `lut` titled `bar_title` and `title` above (wrapped to the picture's width), fits the
    camera to the shown data (zoomed in by `dolly`), renders and saves a `resolution` screenshot to `path`; removes
    the title again."""
    from paraview import simple
    bar = simple.GetScalarBar(lut, view)
    bar.Title = bar_title
    bar.ComponentTitle = ''
    text = simple.Text(registrationName='Title', Text=wrapped_title(title, font_size, resolution[0]))
    text_display = simple.Show(text, view)
    text_display.WindowLocation = 'Upper Center'
    text_display.FontSize = font_size
    view.ResetCamera()
    if dolly != 1.0:
        view.GetActiveCamera().Dolly(dolly)
    simple.Render(view)
    simple.SaveScreenshot(path, view, ImageResolution=resolution)
    simple.Delete(text)


class Colouring(object):
    """How a picture colours one point array: its name, ParaView's preset, the range, the scalar bar's title, and
    the colour of NaN values (RGB in [0, 1])."""

    def __init__(self, array, preset, value_range, bar_title, nan_colour=(0.5, 0.5, 0.5)):
        self.array, self.preset, self.range = array, preset, value_range
        self.bar_title, self.nan_colour = bar_title, nan_colour


# The main job's pictures of a point array: the continuous features, and the shape index at each point's steadiest
# principal direction (NaN grey: no anisotropic scale there, spheres and planes).
FEATURES = Colouring('GLSFeature', 'Inferno (matplotlib)', (0.0, 1.0), 'GLS feature f')
SHAPE_INDEX = Colouring('GLSStableShapeIndex', 'Cool to Warm', (-1.0, 1.0),
                        'shape index (-1 cup, -1/2 valley, 0 saddle, 1/2 ridge, 1 cap)', (0.75, 0.75, 0.75))


def render_point_arrays(polydata, pictures):
    """Pictures of point arrays on the data, one per (path, colouring, title) of `pictures`, each coloured as its
    `colouring` says: its surface when it has polygons, else the points (drawn as vertex cells made for the pictures,
    whatever cells the data has; every k-th point above MAX_SHOWN_POINTS, said in the titles). One view, one shown
    copy of the data and one camera serve them all. Returns the stride k."""
    from paraview import simple
    from vtkmodules.util.numpy_support import vtk_to_numpy
    names = [colouring.array for _, colouring, _ in pictures]
    surface = gls_cloud.has_surface(polydata)
    points = vtk_to_numpy(polydata.GetPoints().GetData())
    normals_array = polydata.GetPointData().GetArray('Normals')
    normals = vtk_to_numpy(normals_array) if normals_array is not None else None
    values = {name: vtk_to_numpy(polydata.GetPointData().GetArray(name)) for name in names}
    note = ''
    # Points without a position (non-finite coordinates: a scanner's missing returns, NaN rows of the output) are
    # not drawn and frame nothing.
    kept = np.isfinite(points).all(axis=1)
    stray = polydata.GetPointData().GetArray('GLSStray')
    if stray is not None and not surface:
        # The stray points the filters left out (far from the rest): not drawn, so that the pictures frame the cloud.
        stray_kept = vtk_to_numpy(stray) == 0
        hidden = np.count_nonzero(~stray_kept & kept)
        note += ' (%d stray point%s not shown)' % (hidden, '' if hidden == 1 else 's')
        kept &= stray_kept
    if not kept.all():
        points = points[kept]
        values = {name: v[kept] for name, v in values.items()}
        normals = normals[kept] if normals is not None else None
    stride = 1 if surface else gls_cloud.stride_for(len(points), MAX_SHOWN_POINTS)
    if stride > 1:
        note += ' (%s shown)' % gls_cloud.every_kth_note(stride)
    shown = polydata if surface else gls_cloud.vertex_cloud(points[::stride],
                                                            {name: v[::stride] for name, v in values.items()})
    source = gls_cloud.producer(shown)
    view = simple.CreateRenderView()
    view.ViewSize = [1200, 900]
    view.OrientationAxesVisibility = 0
    display = simple.Show(source, view)
    if not surface:
        display.SetRepresentationType('Points')
        display.PointSize = 3 if len(points) // stride < 200000 else 2
    aim_camera(view, points, normals)
    for path, colouring, title in pictures:
        simple.ColorBy(display, ('POINTS', colouring.array))
        lut = simple.GetColorTransferFunction(colouring.array)
        lut.ApplyPreset(colouring.preset, True)
        lut.RescaleTransferFunction(*colouring.range)
        lut.NanColor = list(colouring.nan_colour)
        display.SetScalarBarVisibility(view, True)
        save_picture(path, view, lut, colouring.bar_title, title + note, 22, [1200, 900])
        display.SetScalarBarVisibility(view, False)
    simple.Delete(view)
    simple.Delete(source)
    return stride
