"""The main job's denoising stage (the paper's section 6): optional synthetic noise, GLS Adaptive Bandwidth, GLS
Projection, and the before/after picture.

Scales come from the sampling, not from the bounding box: with r the median distance from a point to its 6th
nearest distinct neighbour (measured on up to 2,000 points: the radius whose ball holds the 6 points a fit needs,
whatever the sampling), the bandwidth is searched from r to 4.5 r (40 logarithmic scales) and smoothed over 3.5 r.
On the bunny's vertices (r about 1.15 times the old rule's 1.5 d, d the nearest-neighbour spacing) this denoises
--noise 0.002 from RMS 0.000497 to 0.000182, where the old rule (1.5 d to 8 d, smoothed over 6 d, from the denoising
benchmark) gave 0.000187 and a warning: its smallest scales held 5 neighbours. On a randomly sampled cloud a rule in
d fares worse still (a ball of 2 d holds about 3 points there)."""
import numpy as np

import gls_cloud
import gls_io
import gls_render
import gls_watch

NORMALS = ['POINTS', 'Normals']  # the normals every GLS stage of the main job reads, named (never a guess)
# The bandwidth's search range and smoothing radius, in units of the 6-neighbour radius r.
SPACING_NEIGHBOURS = 6
MIN_BANDWIDTH = 1.0
MAX_BANDWIDTH = 4.5
SMOOTHING = 3.5


def neighbour_radius(polydata, rank=SPACING_NEIGHBOURS, samples=2000, copies=8):
    """Median distance from a point to its rank-th nearest neighbour at a distinct position (length), on an evenly
    spaced subset of the points; copies at the same position are skipped (up to `copies` of them), so coincident
    points do not shrink it. 0 when no sampled point has that many distinct neighbours among its nearest."""
    from vtkmodules.vtkCommonCore import vtkIdList
    from vtkmodules.vtkCommonDataModel import vtkStaticPointLocator
    from vtkmodules.util.numpy_support import vtk_to_numpy
    locator = vtkStaticPointLocator()
    locator.SetDataSet(polydata)
    locator.BuildLocator()
    ids = vtkIdList()
    n = polydata.GetNumberOfPoints()
    points = vtk_to_numpy(polydata.GetPoints().GetData())
    distances = []
    for i in np.linspace(0, n - 1, min(n, samples)).astype(int):
        p = points[i].astype(float)
        locator.FindClosestNPoints(min(n, rank + copies + 1), p, ids)
        near = points[[ids.GetId(k) for k in range(ids.GetNumberOfIds())]].astype(float)
        positive = np.unique(np.linalg.norm(near - p, axis=1))
        positive = positive[positive > 0]
        if len(positive) >= rank:
            distances.append(float(positive[rank - 1]))
    return float(np.median(distances)) if distances else 0.0


def with_noise(polydata, sigma, seed=1):
    """A copy of the cloud moved along its unit normals by Gaussian noise of standard deviation sigma (length);
    the normals are kept. Returns (noisy polydata, reference points, reference unit normals)."""
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    points = vtk_to_numpy(polydata.GetPoints().GetData()).astype(float)
    normals = vtk_to_numpy(polydata.GetPointData().GetArray('Normals')).astype(float)
    normals = normals / np.maximum(np.linalg.norm(normals, axis=1), 1e-300)[:, None]
    moved = points + np.random.default_rng(seed).normal(0.0, sigma, len(points))[:, None] * normals if sigma > 0 \
        else points.copy()
    noisy = vtkPolyData()
    noisy.ShallowCopy(polydata)
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(moved), deep=True))
    noisy.SetPoints(pts)
    return noisy, points, normals


def signed_offsets(points, reference, normals):
    """Signed distance of each point from its reference position along the reference unit normal (length)."""
    return np.einsum('ij,ij->i', points - reference, normals)


def offset_cloud(points, reference, normals, shift):
    """Points (shifted by `shift` for a side-by-side view) carrying GLSOffset: the signed distance along the
    reference normal from the reference position (length)."""
    return gls_cloud.vertex_cloud(points + np.asarray(shift),
                                  {'GLSOffset': signed_offsets(points, reference, normals)})


# The most points the denoising picture is computed on: a larger cloud is denoised from every k-th point (the
# picture shows the whole object at that density; the title says so). 250,000 points at point size 3 fill each
# 800 x 800 half of the picture that the object covers.
MAX_DENOISED_POINTS = 250000


def rows_of(polydata, rows):
    """A vertex cloud of the points `rows` (indices, or a slice) with their numeric point arrays."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    arrays = polydata.GetPointData()
    return gls_cloud.vertex_cloud(
        vtk_to_numpy(polydata.GetPoints().GetData())[rows],
        {arrays.GetArrayName(i): vtk_to_numpy(arrays.GetArray(i))[rows]
         for i in range(arrays.GetNumberOfArrays()) if arrays.GetArray(i) is not None})


def with_normals(polydata):
    """The indices of the points with a finite position and a finite, non-zero normal: those the stage denoises
    (a point whose normal is undefined has no surface to be moved along)."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    points = vtk_to_numpy(polydata.GetPoints().GetData())
    normals = vtk_to_numpy(polydata.GetPointData().GetArray('Normals'))
    return np.flatnonzero(np.isfinite(points).all(axis=1) & np.isfinite(normals).all(axis=1) &
                          (np.abs(normals).sum(axis=1) > 0))


def sample_note(stage):
    """' (every k-th point)' when the stage ran on a subsample, ' (the N points with a normal)' when some points
    had none, else ''."""
    notes = []
    if stage['stride'] > 1:
        notes.append(gls_cloud.every_kth_note(stage['stride']))
    if stage['without_normals'] > 0:
        notes.append('%d point%s without a normal left out' % (stage['without_normals'],
                                                               '' if stage['without_normals'] == 1 else 's'))
    return ' (%s)' % '; '.join(notes) if notes else ''


def denoise(make_proxy, upstream, noise, watch):
    """Runs the stage on the fetched upstream cloud (with Normals). noise: standard deviation of the synthetic
    noise as a fraction of the bounding-box diagonal (0: the input as it is). Returns a dict with the noisy cloud,
    the projection's output, the reference points and normals, the scales used and the wall time; raises
    gls_watch.StageError when a stage reports an error or the points have no distinct neighbours."""
    import time
    from paraview import simple
    rows = with_normals(upstream)
    without_normals = upstream.GetNumberOfPoints() - len(rows)
    if len(rows) < 2:
        raise gls_watch.StageError('denoising: fewer than 2 points have a normal')
    stride = gls_cloud.stride_for(len(rows), MAX_DENOISED_POINTS)
    if stride > 1 or without_normals > 0:
        upstream = rows_of(upstream, rows[::stride])
    diagonal = float(np.sqrt(sum((upstream.GetBounds()[2 * a + 1] - upstream.GetBounds()[2 * a]) ** 2
                                 for a in range(3))))
    noisy, reference, normals = with_noise(upstream, noise * diagonal)
    d = neighbour_radius(noisy)
    if not d > 0:
        raise gls_watch.StageError('denoising: the points have no distinct neighbours (all at one position?)')
    start = time.time()
    source = gls_cloud.producer(noisy)
    bandwidth = make_proxy('GLSAdaptiveBandwidth', registrationName='Bandwidth', Input=source, Normals=NORMALS,
                           ScaleUnits='Absolute', MinScale=MIN_BANDWIDTH * d, MaxScale=MAX_BANDWIDTH * d,
                           NumberOfScales=40, ScaleSampling='Logarithmic', SmoothingRadius=SMOOTHING * d)
    watch.watch(bandwidth, 'adaptive bandwidth')
    projection = make_proxy('GLSProjection', registrationName='Denoised', Input=bandwidth, Normals=NORMALS)
    watch.watch(projection, 'projection')
    watch.update(projection)
    result = gls_io.output_of(projection)
    elapsed = time.time() - start
    for proxy in (projection, bandwidth, source):
        simple.Delete(proxy)
    return {'noisy': noisy, 'denoised': result, 'reference': reference, 'normals': normals, 'spacing': d,
            'sigma': noise * diagonal, 'seconds': elapsed, 'stride': stride, 'without_normals': without_normals}


def offsets(stage):
    """RMS signed distance to the reference (along its normals) before and after, in length units."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    out = {}
    for key in ('noisy', 'denoised'):
        p = vtk_to_numpy(stage[key].GetPoints().GetData()).astype(float)
        offsets = signed_offsets(p, stage['reference'], stage['normals'])
        out[key] = float(np.sqrt(np.mean(offsets[np.isfinite(offsets)] ** 2)))  # a point the projection left NaN
    return out


def render(path, stage, title):
    """Before (left) and after (right) side by side, coloured by the signed distance to the reference."""
    from paraview import simple
    from vtkmodules.util.numpy_support import vtk_to_numpy
    ref, nrm = stage['reference'], stage['normals']
    width = float(np.ptp(ref[:, 0]))
    before = offset_cloud(vtk_to_numpy(stage['noisy'].GetPoints().GetData()).astype(float), ref, nrm, (0, 0, 0))
    after = offset_cloud(vtk_to_numpy(stage['denoised'].GetPoints().GetData()).astype(float), ref, nrm,
                         (1.15 * width, 0, 0))
    limit = 2.0 * stage['sigma'] if stage['sigma'] > 0 else max(
        1e-12, float(np.percentile(np.abs(vtk_to_numpy(after.GetPointData().GetScalars())), 98)))
    view = simple.CreateRenderView()
    view.ViewSize = [1600, 800]
    view.OrientationAxesVisibility = 0
    lut = simple.GetColorTransferFunction('GLSOffset')
    lut.ApplyPreset('Cool to Warm', True)
    lut.RescaleTransferFunction(-limit, limit)
    sources = [gls_cloud.producer(before), gls_cloud.producer(after)]
    for source in sources:
        display = simple.Show(source, view)
        display.SetRepresentationType('Points')
        display.PointSize = 3
        simple.ColorBy(display, ('POINTS', 'GLSOffset'))
        display.SetScalarBarVisibility(view, True)
    gls_render.save_picture(path, view, lut, 'distance to the input surface (length)', title, 20, [1600, 800],
                            dolly=1.7)
    for proxy in sources:
        simple.Delete(proxy)
    simple.Delete(view)
