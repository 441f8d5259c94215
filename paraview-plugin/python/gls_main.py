"""The GLS main job, for pvpython (under Xvfb when there is no display: see the gls-analyze wrapper).

    gls-analyze [input] [--output-dir DIR] [--scales N] [--min-scale F] [--max-scale F] [--sigma S] [--noise F]

Reads a point cloud or mesh (PLY, OBJ, STL, VTP, or a text file: XYZ/PTS/CSV/TXT; default: the bundled bunny
scan), estimates oriented normals when the file has none, computes the GLS scale space (N quadratic scales from
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
Files appear only when every stage succeeded. Exit status: 0 done; 2 the input, the options or a stage's result
cannot be used (one line on stderr says why; nothing written); 1 an internal error (a traceback, nothing
written); 3 no X server could be started. docs/main-job.md has the details (column layouts of text files).
"""
import argparse
import math
import os
import sys
import time
import traceback

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import numpy as np  # noqa: E402

import gls_cloud  # noqa: E402
import gls_coincident  # noqa: E402
import gls_cross_section  # noqa: E402
import gls_denoising  # noqa: E402
import gls_io  # noqa: E402
import gls_outputs  # noqa: E402
import gls_profiles  # noqa: E402
import gls_render  # noqa: E402
import gls_watch  # noqa: E402

NORMALS = gls_denoising.NORMALS


class UsageError(Exception):
    """A bad option value (one line)."""


class AnalysisError(Exception):
    """The analysis ran but its result cannot be used (one line, with the advice)."""


class ArgumentParser(argparse.ArgumentParser):
    def error(self, message):
        raise UsageError(message)


def parse_arguments(argv):
    p = ArgumentParser(prog='gls-analyze', description=__doc__.split('\n\n')[1],
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('input', nargs='?', default=os.environ.get('GLS_DEFAULT_INPUT'),
                   help='point cloud or mesh (default: the bundled bunny)')
    p.add_argument('--output-dir', default='gls-output', help='where the results go (default ./gls-output)')
    p.add_argument('--plugin', default=os.environ.get('GLS_PLUGIN'), help='path of GrowingLeastSquares.so')
    p.add_argument('--scales', type=int, default=20, help='number of scales, at least 2 (default 20)')
    p.add_argument('--min-scale', type=float, default=0.008, help='smallest scale / diagonal, > 0 (default 0.008)')
    p.add_argument('--max-scale', type=float, default=0.08,
                   help='largest scale / diagonal, > --min-scale (default 0.08)')
    p.add_argument('--sigma', type=float, default=None,
                   help='an absolute tanh scale of the features, > 0 (default: relative to the data, so that the '
                        'median feature is 0.28)')
    p.add_argument('--noise', type=float, default=0.0,
                   help='denoising picture: Gaussian noise added along the normals first, standard deviation as a '
                        'fraction of the diagonal, >= 0 (default 0: denoise the input as it is)')
    return p.parse_args(argv)


def validate(args):
    """Raises UsageError for an option value the analysis cannot use, before anything runs."""
    if args.scales < 2:
        raise UsageError('--scales must be at least 2 (the features integrate over the scales); got %d'
                         % args.scales)
    if not (math.isfinite(args.min_scale) and args.min_scale > 0):
        raise UsageError('--min-scale must be a positive fraction of the diagonal; got %g' % args.min_scale)
    if not (math.isfinite(args.max_scale) and args.max_scale > args.min_scale):
        raise UsageError('--max-scale must be larger than --min-scale; got --min-scale %g, --max-scale %g'
                         % (args.min_scale, args.max_scale))
    if args.sigma is not None and not (math.isfinite(args.sigma) and args.sigma > 0):
        raise UsageError('--sigma must be positive; got %g' % args.sigma)
    if not (math.isfinite(args.noise) and args.noise >= 0):
        raise UsageError('--noise must be 0 or positive; got %g' % args.noise)


def gls_filter(name, **properties):
    """Creates a GLS proxy by its paraview.simple name (LoadPlugin put the constructors in this module)."""
    return globals()[name](**properties)


def checked_features(result):
    """The GLSFeature values of the pipeline's output; AnalysisError when there is no finite one."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    pd = result.GetPointData()
    if pd.GetArray('GLSFeature') is None:
        raise AnalysisError('the pipeline gave no features (see the messages above)')
    feature = vtk_to_numpy(pd.GetArray('GLSFeature'))
    if not np.isfinite(feature).any():
        counts = pd.GetArray('GLSNeighborCount')
        scales = vtk_to_numpy(result.GetFieldData().GetArray('GLSScales'))
        median = int(np.median(vtk_to_numpy(counts).reshape(len(feature), -1)[:, -1])) if counts else 0
        raise AnalysisError('no point has a defined feature: at the largest scale (%.4g) the median point has %d '
                            'neighbour(s), too few for a fit (%d points in all); use larger scales (--min-scale, '
                            '--max-scale) or a denser cloud' % (scales[-1], median, result.GetNumberOfPoints()))
    return feature


def analyze(args, outputs):
    """Runs every stage, writing into `outputs`' staging folder; raises InputError, StageError or AnalysisError."""
    from paraview import simple
    from vtkmodules.util.numpy_support import vtk_to_numpy
    simple.LoadPlugin(args.plugin, remote=False, ns=globals())
    watch = gls_watch.Watch()
    source, data, description = gls_io.open_cloud(args.input, gls_filter, watch)
    count = data.GetNumberOfPoints()
    print('input: %s (%d points; %s)' % (args.input, count, description))
    merged = gls_coincident.merge(data)
    if merged is not None:
        print(merged.note())
        source = gls_cloud.producer(merged.polydata)
    analysed = merged.polydata if merged is not None else data
    if analysed.GetNumberOfPoints() < 2:
        raise gls_io.InputError('%s: all %d points are at one position: nothing to analyse' % (args.input, count))

    start = time.time()
    upstream = source
    if not gls_cloud.has_normals(analysed):
        upstream = watch.watch(gls_filter('GLSNormalEstimation', registrationName='Normals', Input=source), 'normals')
    scale_space = watch.watch(gls_filter('GLSScaleSpace', registrationName='ScaleSpace', Input=upstream,
                                         Normals=NORMALS, NumberOfScales=args.scales, MinScale=args.min_scale,
                                         MaxScale=args.max_scale, ScaleSampling='Quadratic'), 'scale space')
    variation = watch.watch(gls_filter('GLSGeometricVariation', registrationName='Variation', Input=scale_space,
                                       Normals=NORMALS), 'geometric variation')
    # --sigma: an absolute sigma; else the filter's default, relative to the data (median feature 0.28).
    sigma = {} if args.sigma is None else {'SigmaMode': 'Absolute', 'Sigma': args.sigma}
    features = watch.watch(gls_filter('GLSContinuousFeatures', registrationName='Features', Input=variation,
                                      Normals=NORMALS, **sigma), 'continuous features')
    features.UpdatePipeline()
    watch.check()
    result = simple.servermanager.Fetch(features)
    feature = checked_features(result)
    elapsed = time.time() - start
    pd = result.GetPointData()
    scales = vtk_to_numpy(result.GetFieldData().GetArray('GLSScales'))
    print('GLS pipeline: %.2f s; %d scales from %.4g to %.4g; feature in [%.3f, %.3f], median %.3f'
          % (elapsed, len(scales), scales[0], scales[-1], np.nanmin(feature), np.nanmax(feature),
             np.nanmedian(feature)))

    output = merged.scatter(result) if merged is not None else result
    if output.GetNumberOfCells() == 0:  # a cloud without cells: vertices, so that ParaView shows the .vtp
        output.SetVerts(gls_cloud.vertex_cells(output.GetNumberOfPoints()))
    vtp = outputs.path('-gls.vtp')
    gls_outputs.write_vtp(vtp, output)
    gls_render.render_features(outputs.path('-features.png'), output,
                               'GLS continuous features: %s (%d points)' % (outputs.name, count))

    picks = gls_profiles.select_profile_points(feature, vtk_to_numpy(pd.GetArray('GLSPertinentScaleCount')))
    profiles = watch.watch(gls_filter('GLSScaleProfiles', registrationName='Profiles', Input=upstream,
                                      Normals=NORMALS, PointIds=list(picks.values()), NumberOfScales=300,
                                      MinScale=args.min_scale, MaxScale=args.max_scale, ScaleSampling='Quadratic'),
                           'scale profiles', progress=False)
    profiles.UpdatePipeline()
    watch.check()
    gls_profiles.plot_profiles(outputs.path('-profiles.png'), 'GLS scale profiles: %s' % outputs.name,
                               simple.servermanager.Fetch(profiles), picks,
                               vtk_to_numpy(pd.GetArray('GLSPertinentScales')))

    cloud = analysed if upstream is source else simple.servermanager.Fetch(upstream)
    stage = gls_denoising.denoise(gls_filter, cloud, args.noise, watch)
    rms = gls_denoising.offsets(stage)
    print('denoising: %.2f s; bandwidth searched from %.4g to %.4g; RMS distance to the input surface %.4g -> %.4g'
          % (stage['seconds'], 1.5 * stage['spacing'], 8.0 * stage['spacing'], rms['noisy'], rms['denoised']))
    gls_denoising.render(outputs.path('-denoising.png'), stage,
                         'GLS denoising: %s%s (left) -> adaptive-bandwidth MLS projection (right)'
                         % (outputs.name, ' + noise %.3g x diagonal' % args.noise if args.noise > 0 else ''))

    curve, axis = gls_cross_section.longest_section(analysed)
    if curve is None:
        print('scale-space image: skipped (the input has no polygons to cut a cross-section from)')
    else:
        image, crossings = gls_cross_section.scale_space_image(gls_filter, curve, watch)
        gls_cross_section.plot(outputs.path('-scale-space.png'),
                               'GLS scale-space image of the central cross-section of %s (%d points)'
                               % (outputs.name, curve.GetNumberOfPoints()), curve, axis, image, crossings)
    gls_outputs.save_state(outputs.path('-gls.pvsm'), vtp, outputs.final('-gls.vtp'))


def fail(message, status=2):
    print('gls-analyze: %s' % message, file=sys.stderr)
    return status


def main(argv):
    try:
        args = parse_arguments(argv)
        validate(args)
    except UsageError as e:
        return fail('%s (gls-analyze --help lists the options)' % e)
    if not args.input:
        return fail('no input given, and no bundled default scan (GLS_DEFAULT_INPUT unset): '
                    'gls-analyze <point cloud or mesh file>')
    if not args.plugin or not os.path.isfile(args.plugin):
        return fail('plugin not found (%s); build the project first' % args.plugin)
    try:
        gls_io.check_file(args.input)
        outputs = gls_outputs.Outputs(args.output_dir, os.path.splitext(os.path.basename(args.input))[0])
    except (gls_io.InputError, gls_outputs.OutputError) as e:
        return fail(e)
    try:
        analyze(args, outputs)
    except (gls_io.InputError, gls_watch.StageError, AnalysisError) as e:
        outputs.discard()
        return fail('%s; no results written' % e)
    except BaseException as e:
        outputs.discard()
        if isinstance(e, (KeyboardInterrupt, SystemExit)):
            raise
        traceback.print_exc()
        return fail('internal error (the traceback above); no results written', 1)
    for path in outputs.commit():
        print('wrote %s' % path)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
