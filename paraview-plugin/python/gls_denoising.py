"""The main job's denoising stage (the paper's section 6): optional synthetic noise, GLS Adaptive Bandwidth, GLS
Projection, and the before/after picture.

Scales come from the sampling, not from the bounding box: with d the median distance of a point to its nearest
neighbour (measured on up to 2,000 points), the bandwidth is searched from 1.5 d to 8 d (40 logarithmic scales) and
smoothed over 6 d -- the ranges of the denoising benchmark (Testing/Benchmarks/glsDenoisingBenchmark.cxx), where
this rule beats every single global scale."""
import numpy as np

import gls_cloud
import gls_render
import gls_watch

NORMALS = ['POINTS', 'Normals']  # the normals every GLS stage of the main job reads, named (never a guess)


def nearest_neighbour_distance(polydata, samples=2000, neighbours=16):
    """Median distance from a point to its nearest neighbour at a positive distance (length), on an evenly spaced
    subset of the points; copies at the same position are skipped (up to `neighbours` - 1 of them), so coincident
    points do not make it 0. 0 when no sampled point has a distinct neighbour among its nearest."""
    from vtkmodules.vtkCommonCore import vtkIdList
    from vtkmodules.vtkCommonDataModel import vtkStaticPointLocator
    locator = vtkStaticPointLocator()
    locator.SetDataSet(polydata)
    locator.BuildLocator()
    ids = vtkIdList()
    n = polydata.GetNumberOfPoints()
    distances = []
    for i in np.linspace(0, n - 1, min(n, samples)).astype(int):
        p = np.array(polydata.GetPoint(int(i)))
        locator.FindClosestNPoints(min(n, neighbours), p, ids)
        gaps = [np.linalg.norm(np.subtract(polydata.GetPoint(ids.GetId(k)), p)) for k in range(ids.GetNumberOfIds())]
        positive = [d for d in gaps if d > 0]
        if positive:
            distances.append(float(min(positive)))
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


def denoise(make_proxy, upstream, noise, watch):
    """Runs the stage on the fetched upstream cloud (with Normals). noise: standard deviation of the synthetic
    noise as a fraction of the bounding-box diagonal (0: the input as it is). Returns a dict with the noisy cloud,
    the projection's output, the reference points and normals, the scales used and the wall time; raises
    gls_watch.StageError when a stage reports an error or the points have no distinct neighbours."""
    import time
    from paraview import simple
    diagonal = float(np.sqrt(sum((upstream.GetBounds()[2 * a + 1] - upstream.GetBounds()[2 * a]) ** 2
                                 for a in range(3))))
    noisy, reference, normals = with_noise(upstream, noise * diagonal)
    d = nearest_neighbour_distance(noisy)
    if not d > 0:
        raise gls_watch.StageError('denoising: the points have no distinct neighbours (all at one position?)')
    start = time.time()
    source = gls_cloud.producer(noisy)
    bandwidth = make_proxy('GLSAdaptiveBandwidth', registrationName='Bandwidth', Input=source, Normals=NORMALS,
                           ScaleUnits='Absolute', MinScale=1.5 * d, MaxScale=8.0 * d, NumberOfScales=40,
                           ScaleSampling='Logarithmic', SmoothingRadius=6.0 * d)
    watch.watch(bandwidth, 'adaptive bandwidth')
    projection = make_proxy('GLSProjection', registrationName='Denoised', Input=bandwidth, Normals=NORMALS)
    watch.watch(projection, 'projection')
    projection.UpdatePipeline()
    watch.check()
    result = simple.servermanager.Fetch(projection)
    elapsed = time.time() - start
    for proxy in (projection, bandwidth, source):
        simple.Delete(proxy)
    return {'noisy': noisy, 'denoised': result, 'reference': reference, 'normals': normals, 'spacing': d,
            'sigma': noise * diagonal, 'seconds': elapsed}


def offsets(stage):
    """RMS signed distance to the reference (along its normals) before and after, in length units."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    out = {}
    for key in ('noisy', 'denoised'):
        p = vtk_to_numpy(stage[key].GetPoints().GetData()).astype(float)
        out[key] = float(np.sqrt(np.mean(signed_offsets(p, stage['reference'], stage['normals']) ** 2)))
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
