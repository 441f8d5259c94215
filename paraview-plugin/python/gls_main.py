"""The GLS main job, for pvpython (under Xvfb when there is no display: see the gls-analyze wrapper).

    gls-analyze [input] [--output-dir DIR] [--scales N] [--min-scale F] [--max-scale F] [--sigma S] [--noise F]

Reads a point cloud or mesh (PLY, OBJ, VTP, XYZ/CSV with or without normals; default: the bundled bunny scan),
estimates oriented normals when the file has none, computes the GLS scale space (N quadratic scales from
--min-scale to --max-scale, fractions of the bounding-box diagonal), the geometric variation and the continuous
features, and writes to the output directory:
  <name>-gls.vtp        every array (inline binary VTK XML)
  <name>-features.png   the continuous features on the cloud (colour map, scalar bar, title)
  <name>-profiles.png   kappa and nu against 300 scales for a few selected points (GLS Scale Profiles; the
                        paper's Figures 2-3 style)
  <name>-denoising.png  before/after of the denoising (GLS Adaptive Bandwidth + GLS Projection) on the cloud,
                        after adding Gaussian noise of --noise x diagonal along the normals (default 0: as it is)
  <name>-scale-space.png  a mesh only: the scale-space image (t*kappa against arclength and scale, zero crossings
                        of kappa) of its central cross-section (GLS Scale Space Image; the paper's Figures 6-8)
  <name>-gls.pvsm       a ParaView state that opens the .vtp coloured by the features
"""
import argparse
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import numpy as np  # noqa: E402

import gls_cross_section  # noqa: E402
import gls_denoising  # noqa: E402
import gls_io  # noqa: E402
import gls_render  # noqa: E402


def parse_arguments(argv):
    p = argparse.ArgumentParser(prog='gls-analyze', description=__doc__.split('\n\n')[1],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('input', nargs='?', default=os.environ.get('GLS_DEFAULT_INPUT'),
                   help='point cloud or mesh (default: the bundled bunny)')
    p.add_argument('--output-dir', default='gls-output', help='where the results go (default ./gls-output)')
    p.add_argument('--plugin', default=os.environ.get('GLS_PLUGIN'), help='path of GrowingLeastSquares.so')
    p.add_argument('--scales', type=int, default=20, help='number of scales (default 20)')
    p.add_argument('--min-scale', type=float, default=0.008, help='smallest scale / diagonal (default 0.008)')
    p.add_argument('--max-scale', type=float, default=0.08, help='largest scale / diagonal (default 0.08)')
    p.add_argument('--sigma', type=float, default=0.1, help='tanh scale of the features (default 0.1)')
    p.add_argument('--noise', type=float, default=0.0,
                   help='denoising picture: Gaussian noise added along the normals first, standard deviation as a '
                        'fraction of the diagonal (default 0: denoise the input as it is)')
    return p.parse_args(argv)


class Progress:
    """A progress line on the terminal (redrawn in place), one line per quarter when not a terminal."""

    def __init__(self):
        self.tty = sys.stderr.isatty()
        self.last = None

    def watch(self, proxy, label):
        algorithm = proxy.GetClientSideObject()

        def report(obj, _event):
            step = int(obj.GetProgress() * (100 if self.tty else 4))
            if (label, step) == self.last:
                return
            self.last = (label, step)
            pct = 100.0 * obj.GetProgress()
            if self.tty:
                sys.stderr.write('\r  %-24s %3.0f%%%s' % (label, pct, '\n' if pct >= 100 else ''))
            else:
                sys.stderr.write('  %-24s %3.0f%%\n' % (label, pct))
            sys.stderr.flush()

        algorithm.AddObserver('ProgressEvent', report)


def gls_filter(name, **properties):
    """Creates a GLS proxy by its paraview.simple name (LoadPlugin put the constructors in this module)."""
    return globals()[name](**properties)


def has_normals(source):
    info = source.GetDataInformation().GetPointDataInformation()
    for i in range(info.GetNumberOfArrays()):
        a = info.GetArrayInformation(i)
        if a.GetName() == 'Normals' and a.GetNumberOfComponents() == 3:
            return True
    return False


def select_profile_points(feature, pertinent_count):
    """A few telling points: the flattest, the most featured, a median one, one with several pertinent scales."""
    valid = np.where(np.isfinite(feature))[0]
    order = valid[np.argsort(feature[valid], kind='stable')]
    picks = {'lowest feature': int(order[0]), 'median feature': int(order[len(order) // 2]),
             'highest feature': int(order[-1])}
    several = np.where(pertinent_count >= 2)[0]
    if len(several):
        picks['2+ pertinent scales'] = int(several[len(several) // 2])
    return picks


def plot_profiles(path, title, table, picks, pertinent):
    """kappa and nu against scale for the picked points, from a GLS Scale Profiles table (finely sampled)."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    from vtkmodules.util.numpy_support import vtk_to_numpy

    def column(name):
        return vtk_to_numpy(table.GetColumnByName(name))

    t = column('t')
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    for label, pid in picks.items():
        line, = ax1.plot(t, column('t*kappa (%d)' % pid) / t, label='%s (point %d)' % (label, pid))
        ax2.semilogy(t, np.maximum(column('nu (%d)' % pid), 1e-12), color=line.get_color())
        for scale in pertinent[pid]:
            if np.isfinite(scale):
                ax2.axvline(scale, color=line.get_color(), ls=':', lw=1)
    ax1.set_ylabel('kappa (1/length)')
    ax1.axhline(0, color='gray', lw=0.5)
    ax1.legend(fontsize=8)
    ax1.set_title(title)
    ax2.set_ylabel('nu (dimensionless, log)')
    ax2.set_xlabel('scale t (length), %d scales; dotted: pertinent scales' % len(t))
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def render_features(path, source, title):
    from paraview import simple
    view = simple.CreateRenderView()
    view.ViewSize = [1200, 900]
    view.OrientationAxesVisibility = 0
    display = simple.Show(source, view)
    if source.GetDataInformation().GetNumberOfCells() == source.GetDataInformation().GetNumberOfPoints():
        display.SetRepresentationType('Points')
        display.PointSize = 3
    simple.ColorBy(display, ('POINTS', 'GLSFeature'))
    lut = simple.GetColorTransferFunction('GLSFeature')
    lut.ApplyPreset('Inferno (matplotlib)', True)
    lut.RescaleTransferFunction(0.0, 1.0)
    display.SetScalarBarVisibility(view, True)
    gls_render.save_picture(path, view, lut, 'GLS feature f', title, 22, [1200, 900])
    simple.Delete(view)


def write_vtp(path, polydata):
    """Inline binary VTK XML (ParaView 5.11's reader fails on some appended files). Reading it back, ParaView 5.11
    prints a harmless "Error reading InformationKey ... L2_NORM_RANGE" for the vector arrays: its writer stores
    that range cache and its reader does not know the key; the data are read correctly."""
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(polydata)
    writer.SetDataModeToBinary()
    writer.SetCompressorTypeToZLib()
    writer.SetHeaderTypeToUInt64()
    if writer.Write() != 1:
        raise IOError('cannot write %s' % path)


def save_state(path, vtp):
    """A state that opens the written .vtp coloured by the features (no plugin needed to open it)."""
    from paraview import simple
    simple.ResetSession()
    reader = simple.XMLPolyDataReader(registrationName=os.path.basename(vtp), FileName=[os.path.abspath(vtp)])
    view = simple.GetActiveViewOrCreate('RenderView')
    display = simple.Show(reader, view)
    simple.ColorBy(display, ('POINTS', 'GLSFeature'))
    lut = simple.GetColorTransferFunction('GLSFeature')
    lut.ApplyPreset('Inferno (matplotlib)', True)
    lut.RescaleTransferFunction(0.0, 1.0)
    display.SetScalarBarVisibility(view, True)
    view.ResetCamera()
    simple.SaveState(path)


def main(argv):
    args = parse_arguments(argv)
    if not args.input:
        print('gls-analyze: no input given, and no bundled default scan (GLS_DEFAULT_INPUT unset): '
              'gls-analyze <point cloud or mesh file>', file=sys.stderr)
        return 2
    if not args.plugin or not os.path.isfile(args.plugin):
        print('gls-analyze: plugin not found (%s); build the project first' % args.plugin, file=sys.stderr)
        return 2
    from paraview import simple
    simple.LoadPlugin(args.plugin, remote=False, ns=globals())
    try:
        source = gls_io.open_cloud(args.input, gls_filter)
    except gls_io.InputError as e:
        print('gls-analyze: %s' % e, file=sys.stderr)
        return 2
    os.makedirs(args.output_dir, exist_ok=True)
    name = os.path.splitext(os.path.basename(args.input))[0]
    out = lambda suffix: os.path.join(args.output_dir, name + suffix)  # noqa: E731
    count = source.GetDataInformation().GetNumberOfPoints()
    print('input: %s (%d points)' % (args.input, count))

    progress = Progress()
    start = time.time()
    upstream = source
    if not has_normals(source):
        upstream = gls_filter('GLSNormalEstimation', registrationName='Normals', Input=source)
        progress.watch(upstream, 'normals')
    scale_space = gls_filter('GLSScaleSpace', registrationName='ScaleSpace', Input=upstream, NumberOfScales=args.scales,
                                       MinScale=args.min_scale, MaxScale=args.max_scale,
                                       ScaleSampling='Quadratic')
    progress.watch(scale_space, 'scale space')
    variation = gls_filter('GLSGeometricVariation', registrationName='Variation', Input=scale_space)
    progress.watch(variation, 'geometric variation')
    features = gls_filter('GLSContinuousFeatures', registrationName='Features', Input=variation, Sigma=args.sigma)
    progress.watch(features, 'continuous features')
    features.UpdatePipeline()
    result = simple.servermanager.Fetch(features)
    if result.GetPointData().GetArray('GLSFeature') is None:
        print('gls-analyze: the pipeline failed (see the messages above)', file=sys.stderr)
        return 1
    elapsed = time.time() - start

    from vtkmodules.util.numpy_support import vtk_to_numpy
    pd = result.GetPointData()
    feature = vtk_to_numpy(pd.GetArray('GLSFeature'))
    scales = vtk_to_numpy(result.GetFieldData().GetArray('GLSScales'))
    print('GLS pipeline: %.2f s; %d scales from %.4g to %.4g; feature in [%.3f, %.3f], median %.3f'
          % (elapsed, len(scales), scales[0], scales[-1], np.nanmin(feature), np.nanmax(feature),
             np.nanmedian(feature)))

    vtp = out('-gls.vtp')
    write_vtp(vtp, result)
    print('wrote %s' % vtp)
    png = out('-features.png')
    render_features(png, features, 'GLS continuous features: %s (%d points)' % (name, count))
    print('wrote %s' % png)
    picks = select_profile_points(feature, vtk_to_numpy(pd.GetArray('GLSPertinentScaleCount')))
    profiles = gls_filter('GLSScaleProfiles', registrationName='Profiles', Input=upstream,
                          PointIds=list(picks.values()), NumberOfScales=300, MinScale=args.min_scale,
                          MaxScale=args.max_scale, ScaleSampling='Quadratic')
    profiles.UpdatePipeline()
    chart = out('-profiles.png')
    plot_profiles(chart, 'GLS scale profiles: %s' % name, simple.servermanager.Fetch(profiles), picks,
                  vtk_to_numpy(pd.GetArray('GLSPertinentScales')))
    print('wrote %s' % chart)

    mesh = simple.servermanager.Fetch(source)
    cloud = mesh if upstream is source else simple.servermanager.Fetch(upstream)
    stage = gls_denoising.denoise(gls_filter, cloud, args.noise, progress)
    rms = gls_denoising.offsets(stage)
    print('denoising: %.2f s; bandwidth searched from %.4g to %.4g; RMS distance to the input surface %.4g -> %.4g'
          % (stage['seconds'], 1.5 * stage['spacing'], 8.0 * stage['spacing'], rms['noisy'], rms['denoised']))
    picture = out('-denoising.png')
    gls_denoising.render(picture, stage, 'GLS denoising: %s%s (left) -> adaptive-bandwidth MLS projection (right)'
                         % (name, ' + noise %.3g x diagonal' % args.noise if args.noise > 0 else ''))
    print('wrote %s' % picture)

    curve, axis = gls_cross_section.longest_section(mesh)
    if curve is None:
        print('scale-space image: skipped (the input has no polygons to cut a cross-section from)')
    else:
        image, crossings = gls_cross_section.scale_space_image(gls_filter, curve)
        picture = out('-scale-space.png')
        gls_cross_section.plot(picture, 'GLS scale-space image of the central cross-section of %s (%d points)'
                               % (name, curve.GetNumberOfPoints()), curve, axis, image, crossings)
        print('wrote %s' % picture)

    state = out('-gls.pvsm')
    save_state(state, vtp)
    print('wrote %s' % state)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
