"""The main job's scale-space image (the paper's Figures 6-8) of a cross-section of the input mesh: the mesh is cut
by the plane through its bounding-box centre across its smallest extent, the longest resulting polyline is kept,
and GLS Scale Space Image gives kappa against arclength and scale, with the zero crossings of kappa."""
import numpy as np

import gls_cloud


def longest_section(mesh):
    """The longest polyline of the mesh's central cross-section as a vtkPolyData with one polyline cell (its last
    id equal to its first when the section is closed), and the plane's normal axis; (None, None) when the input
    has no polygons or the cut gives no polyline of at least 20 points."""
    from vtkmodules.vtkCommonCore import vtkIdList, vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPlane, vtkPolyData
    from vtkmodules.vtkFiltersCore import vtkCutter, vtkStripper
    if mesh.GetNumberOfPolys() == 0:
        return None, None
    b = mesh.GetBounds()
    extent = [b[2 * a + 1] - b[2 * a] for a in range(3)]
    axis = int(np.argmin(extent))
    plane = vtkPlane()
    plane.SetOrigin([(b[2 * a] + b[2 * a + 1]) / 2 for a in range(3)])
    plane.SetNormal([1.0 if a == axis else 0.0 for a in range(3)])
    cutter = vtkCutter()
    cutter.SetInputData(mesh)
    cutter.SetCutFunction(plane)
    stripper = vtkStripper()
    stripper.SetInputConnection(cutter.GetOutputPort())
    stripper.JoinContiguousSegmentsOn()
    stripper.Update()
    lines = stripper.GetOutput()
    best, best_length = None, 0.0
    ids = vtkIdList()
    lines.GetLines().InitTraversal()
    while lines.GetLines().GetNextCell(ids):
        pts = np.array([lines.GetPoint(ids.GetId(k)) for k in range(ids.GetNumberOfIds())])
        length = float(np.sum(np.linalg.norm(np.diff(pts, axis=0), axis=1))) if len(pts) > 1 else 0.0
        if length > best_length:
            best = ([ids.GetId(k) for k in range(ids.GetNumberOfIds())], pts)
            best_length = length
    if best is None or len(best[1]) < 20:
        return None, None
    order, pts = best
    closed = order[0] == order[-1]
    if closed:
        pts = pts[:-1]
    # The cut repeats a position where the plane passes through a mesh vertex (two edges meet there): each position
    # once, in the order of the polyline.
    _, first = np.unique(pts, axis=0, return_index=True)
    pts = pts[np.sort(first)]
    curve = vtkPolyData()
    points = vtkPoints()
    points.SetDataTypeToDouble()
    for p in pts:
        points.InsertNextPoint(p)
    curve.SetPoints(points)
    cells = vtkCellArray()
    cells.InsertNextCell(len(pts) + (1 if closed else 0))
    for i in range(len(pts)):
        cells.InsertCellPoint(i)
    if closed:
        cells.InsertCellPoint(0)
    curve.SetLines(cells)
    return curve, axis


def scale_space_image(make_proxy, curve, watch, scales=200, min_scale=0.005, max_scale=0.15):
    """Runs GLS Scale Space Image on the curve (scales linear, fractions of the curve's bounding-box diagonal);
    returns (image, zero crossings) as VTK data; raises gls_watch.StageError when the filter reports an error."""
    from paraview import simple
    source = gls_cloud.producer(curve)
    image = make_proxy('GLSScaleSpaceImage', registrationName='CrossSection', Input=source,
                       NumberOfScales=scales, MinScale=min_scale, MaxScale=max_scale)
    watch.watch(image, 'scale-space image', progress=False)
    watch.update(image)
    result = (simple.servermanager.Fetch(image, idx=0), simple.servermanager.Fetch(image, idx=1))
    simple.Delete(image)
    simple.Delete(source)
    return result


def plot(path, title, curve, axis, image, crossings):
    """Left: the section in its plane, coloured by arclength (the image's x). Right: t*kappa against arclength
    and scale, with the zero crossings of kappa in black."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    from vtkmodules.util.numpy_support import vtk_to_numpy
    nx, ny, _ = image.GetDimensions()
    origin, spacing = image.GetOrigin(), image.GetSpacing()
    scaled = vtk_to_numpy(image.GetPointData().GetArray('GLSScaledKappa')).reshape(ny, nx)
    s_max = origin[0] + spacing[0] * (nx - 1)
    t0, t1 = origin[1], origin[1] + spacing[1] * (ny - 1)
    finite = scaled[np.isfinite(scaled)]
    limit = float(np.percentile(np.abs(finite), 98)) if finite.size else 1.0

    pts = vtk_to_numpy(curve.GetPoints().GetData())
    u, v = [a for a in range(3) if a != axis]
    arclength = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(13, 5.2), gridspec_kw={'width_ratios': [1, 2.2]})
    ax1.scatter(pts[:, u], pts[:, v], c=arclength, cmap='viridis', s=3)
    ax1.plot(pts[0, u], pts[0, v], 'ko', ms=5)
    ax1.set_aspect('equal')
    ax1.set_title('section (plane normal %s; dot: arclength 0)' % 'xyz'[axis], fontsize=9)
    ax1.set_xlabel('xyz'[u])
    ax1.set_ylabel('xyz'[v])
    shown = ax2.imshow(np.ma.masked_invalid(scaled), origin='lower', aspect='auto', cmap='RdBu_r',
                       vmin=-limit, vmax=limit, extent=[origin[0], s_max, t0, t1], interpolation='nearest')
    lines = crossings.GetLines()
    if lines is not None:
        from vtkmodules.vtkCommonCore import vtkIdList
        ids = vtkIdList()
        lines.InitTraversal()
        while lines.GetNextCell(ids):
            xy = np.array([crossings.GetPoint(ids.GetId(k))[:2] for k in range(ids.GetNumberOfIds())])
            ax2.plot(xy[:, 0], xy[:, 1], 'k-', lw=0.6)
    ax2.set_xlim(origin[0], s_max)
    ax2.set_ylim(t0, t1)
    ax2.set_xlabel('arclength s (length)')
    ax2.set_ylabel('scale t (length)')
    ax2.set_title(title, fontsize=10)
    fig.colorbar(shown, ax=ax2, label='t * kappa (dimensionless); black: kappa = 0')
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
