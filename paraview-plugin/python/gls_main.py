"""The GLS main job, for pvpython (under Xvfb when there is no display: see the gls-analyze wrapper).

    gls-analyze [input] [--output-dir DIR] [--scales N] [--min-scale F] [--max-scale F] [--absolute-scales]
                [--sigma S] [--noise F]
                [--per-scale] [--full-precision] [--query ID] [--memory-budget GIB] [--no-directions]
                [--orientation auto|up|ground|sensor|mst] [--output-format vtp,las,ply]

Reads a point cloud or mesh (PLY, OBJ, STL, VTP, a text file: XYZ/PTS/CSV/TXT, a scanner's file: LAS, PTX, PCD;
default: the bundled bunny scan), estimates oriented normals when the file has none, analyses N quadratic scales
from --min-scale to --max-scale (fractions of the bounding-box diagonal, or lengths with --absolute-scales) in one
fused pass that stores nothing per scale (the continuous
features, the per-point scale summary and, unless --no-directions, each point's steadiest principal direction over
the scales and the shape index there; memory is checked first), and writes to the output directory:
  <name>-gls.vtp        the points, the input's arrays, normals, GLSFeature and the per-point summaries (float32
                        rounded to a relative 1.2e-4, compressed: about 39 bytes a point on a cloud); every
                        scale's arrays too with --per-scale
  <name>-features.png   the continuous features on the cloud (colour map, scalar bar, title)
  <name>-shape-index.png  the shape index at each point's steadiest principal direction (ridges, valleys, saddles,
                        caps, cups; grey where no scale is anisotropic); not with --no-directions
  <name>-profiles.png   kappa and nu against 300 scales for a few selected points (GLS Scale Profiles; the
                        paper's Figures 2-3 style)
  <name>-denoising.png  before/after of the denoising (GLS Adaptive Bandwidth + GLS Projection) on the cloud,
                        after adding Gaussian noise of --noise x diagonal along the normals (default 0: as it is)
  <name>-scale-space.png  a mesh only: the scale-space image (t*kappa against arclength and scale, zero crossings
                        of kappa) of its central cross-section (GLS Scale Space Image; the paper's Figures 6-8)
  <name>-gls.pvsm       a ParaView state that opens the .vtp coloured by the features
Files appear only when every stage succeeded. Exit status: 0 done; 130 interrupted (Ctrl-C, nothing written); 2 the input, the options or a stage's result
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
import gls_memory  # noqa: E402
import gls_outputs  # noqa: E402
import gls_profiles  # noqa: E402
import gls_render  # noqa: E402
import gls_watch  # noqa: E402

NORMALS = gls_denoising.NORMALS


# --orientation: GLS Normal Estimation's Orientation for each choice ('sensor': orientation_properties).
ORIENTATIONS = {'auto': 'Automatic', 'up': 'Up, walls along the spanning tree', 'ground': 'Spanning tree, ground up',
                'sensor': None, 'mst': 'Minimum spanning tree'}


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
    p.add_argument('--scales', type=int, default=20,
                   help='number of scales, at least 2 (default 20; each adds a small fit per point: thousands of '
                        'scales cost about 0.5 microseconds a point each)')
    p.add_argument('--min-scale', type=float, default=None,
                   help='smallest scale / diagonal, > 0 (default 0.008); with --absolute-scales a length')
    p.add_argument('--max-scale', type=float, default=None,
                   help='largest scale / diagonal, > --min-scale (default 0.08); with --absolute-scales a length')
    p.add_argument('--absolute-scales', action='store_true',
                   help='--min-scale and --max-scale (both then required) are lengths in the units of the data '
                        '(metres on a survey), not fractions of its diagonal')
    p.add_argument('--sigma', type=float, default=None,
                   help='an absolute tanh scale of the features, > 0 (default: relative to the data, so that the '
                        'median feature is 0.28)')
    p.add_argument('--per-scale', action='store_true',
                   help='also store every scale (the scale space and nu: about %d bytes per point and scale) '
                        'instead of the per-point summaries only' % gls_memory.PER_SCALE_BYTES_PER_POINT_SCALE)
    p.add_argument('--full-precision', action='store_true',
                   help='keep every bit of the float32 summaries (default: the descriptors rounded to a relative '
                        '1.2e-4 and the normals to 2^-17, about 39 bytes a point instead of 47)')
    p.add_argument('--query', type=int, default=None,
                   help='a point id: adds GLSDissimilarity, how unlike that point every point is across the scales')
    p.add_argument('--memory-budget', type=float, default=None,
                   help='GiB the analysis may use (default: the memory available when it starts); checked before '
                        'any stage runs')
    p.add_argument('--orientation', choices=ORIENTATIONS, default='auto',
                   help='which side the estimated normals face: auto (default: from what the file says, in this '
                        'order: each point\'s scanner (PTX), the file\'s sensor (a PCD\'s VIEWPOINT), up for '
                        'airborne lidar (a LAS file\'s scan angles, returns or ground class), the spanning tree '
                        'with the ground up for other lidar files, else the minimum spanning tree), up '
                        '(ground and roofs up, walls along the spanning tree: airborne scans), ground (the spanning '
                        'tree with the ground or floor up: terrestrial scans, rooms), sensor (towards the file\'s '
                        'scanner positions; refused when it has none) or mst (the minimum spanning tree)')
    p.add_argument('--output-format', default='vtp',
                   help='the data files to write, a comma list of vtp (VTK XML polydata, with the ParaView state), las '
                        '(LAS 1.4: the GLS arrays as Extra Bytes fields; a LAS input\'s positions, attributes and '
                        'coordinate system kept) and ply (binary PLY: the GLS arrays as scalar_<name> properties, '
                        'which CloudCompare loads as scalar fields); default vtp')
    p.add_argument('--no-directions', action='store_true',
                   help='leave the principal curvatures out of the fused pass (they make it about 1.9 times as '
                        'long) and with them the direction arrays and the shape-index picture')
    p.add_argument('--noise', type=float, default=0.0,
                   help='denoising picture: Gaussian noise added along the normals first, standard deviation as a '
                        'fraction of the diagonal, >= 0 (default 0: denoise the input as it is)')
    return p.parse_args(argv)


def validate(args):
    """Raises UsageError for an option value the analysis cannot use, before anything runs (and fills in the
    relative scales' defaults)."""
    if args.absolute_scales and (args.min_scale is None or args.max_scale is None):
        raise UsageError('--absolute-scales needs --min-scale and --max-scale, lengths in the units of the data')
    if args.min_scale is None:
        args.min_scale = 0.008
    if args.max_scale is None:
        args.max_scale = 0.08
    if args.scales < 2:
        raise UsageError('--scales must be at least 2 (the features integrate over the scales); got %d'
                         % args.scales)
    if not (math.isfinite(args.min_scale) and args.min_scale > 0):
        raise UsageError('--min-scale must be a positive %s; got %g' % (
            'length' if args.absolute_scales else 'fraction of the diagonal', args.min_scale))
    if not (math.isfinite(args.max_scale) and args.max_scale > args.min_scale):
        raise UsageError('--max-scale must be larger than --min-scale; got --min-scale %g, --max-scale %g'
                         % (args.min_scale, args.max_scale))
    if args.sigma is not None and not (math.isfinite(args.sigma) and args.sigma > 0):
        raise UsageError('--sigma must be positive; got %g' % args.sigma)
    if args.memory_budget is not None and not (math.isfinite(args.memory_budget) and args.memory_budget > 0):
        raise UsageError('--memory-budget must be a positive number of GiB; got %g' % args.memory_budget)
    if args.query is not None and args.query < 0:
        raise UsageError('--query must be a point id (0 or more); got %d' % args.query)
    if not (math.isfinite(args.noise) and args.noise >= 0):
        raise UsageError('--noise must be 0 or positive; got %g' % args.noise)
    formats = [f.strip().lower() for f in args.output_format.split(',') if f.strip()]
    unknown = [f for f in formats if f not in gls_outputs.FORMATS]
    if unknown or not formats:
        raise UsageError('--output-format takes a comma list of %s; got %r' % (', '.join(gls_outputs.FORMATS),
                                                                           args.output_format))
    args.output_format = list(dict.fromkeys(formats))  # in the given order, once each


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


def scale_range(args, **more):
    """The filters' scale properties of the options (relative to the diagonal, or lengths with --absolute-scales)."""
    return dict(MinScale=args.min_scale, MaxScale=args.max_scale, ScaleSampling='Quadratic',
                ScaleUnits='Absolute' if args.absolute_scales else 'Relative to bounding box diagonal', **more)


def summary_pipeline(args, upstream, watch, budget):
    """The default path: one fused pass (GLS Continuous Features with ScaleSummary, and DirectionSummary unless
    --no-directions) that stores nothing per scale, within what `budget` (bytes, or None) leaves (its fit cut into
    spatial tiles if need be)."""
    sigma = {} if args.sigma is None else {'SigmaMode': 'Absolute', 'Sigma': args.sigma}
    return watch.watch(gls_filter('GLSContinuousFeatures', registrationName='Features', Input=upstream,
                                  Normals=NORMALS, NumberOfScales=args.scales, ScaleSummary=1,
                                  DirectionSummary=0 if args.no_directions else 1,
                                  OutputPrecision='Single', MemoryBudget=gls_memory.filter_budget_mib(budget),
                                  **scale_range(args, **sigma)),
                       'features and summary')


def per_scale_pipeline(args, upstream, watch, budget):
    """--per-scale: the scale space and nu stored at every scale, then the features and the summary from them."""
    scale_space = watch.watch(gls_filter('GLSScaleSpace', registrationName='ScaleSpace', Input=upstream,
                                         Normals=NORMALS, NumberOfScales=args.scales, **scale_range(args)),
                              'scale space')
    variation = watch.watch(gls_filter('GLSGeometricVariation', registrationName='Variation', Input=scale_space,
                                       Normals=NORMALS), 'geometric variation')
    return summary_pipeline(args, variation, watch, budget)


def report_directions(args, pd):
    """Prints what the fused pass found of the steadiest principal directions (DirectionSummary; not with
    --no-directions)."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    if args.no_directions:
        return
    ridge_valley = vtk_to_numpy(pd.GetArray('GLSRidgeValley'))  # at least 2 points (checked before the analysis)
    print('principal directions: a steadiest direction at %.1f%% of the points (the rest isotropic at every scale: '
          'spheres, planes), %.1f%% on ridges, %.1f%% in valleys'
          % (100.0 * np.mean(np.isfinite(ridge_valley)), 100.0 * np.mean(ridge_valley == 1),
             100.0 * np.mean(ridge_valley == -1)))


def orientation_properties(args, cloud):
    """GLS Normal Estimation's orientation properties for --orientation on `cloud` (the analysed points); InputError
    for 'sensor' when the file gives no scanner position."""
    if args.orientation != 'sensor':
        return dict(Orientation=ORIENTATIONS[args.orientation])
    if cloud.GetPointData().GetArray('ScannerPosition') is not None:
        return dict(Orientation='Towards per-point viewpoints', ViewpointArray=['POINTS', 'ScannerPosition'])
    sensor = cloud.GetFieldData().GetArray('ScannerPosition')
    if sensor is not None and sensor.GetNumberOfTuples() == 1 and sensor.GetNumberOfComponents() == 3:
        return dict(Orientation='Towards point', OrientationPoint=list(sensor.GetTuple3(0)))
    raise gls_io.InputError('--orientation sensor: %s gives no scanner position (PTX scans and PCD files do); use '
                            '--orientation auto, up or mst' % args.input)


def check_query(args, count, merged=None):
    """InputError when --query is not a point of the input (`count` points), or (with `merged`) is a point left out
    for its non-finite coordinates; checked before any stage runs."""
    if args.query is None:
        return
    if not 0 <= args.query < count:
        raise gls_io.InputError('--query %d is not a point of the input (0 to %d)' % (args.query, count - 1))
    if merged is not None and merged.distinct_of([args.query])[0] < 0:
        raise gls_io.InputError('--query %d is a point with a non-finite coordinate (a missing return): it is left '
                                'out of the analysis; choose another point' % args.query)


def query_dissimilarity(args, upstream, watch, merged):
    """GLSDissimilarity of every point to --query (a point id of the input file, checked by check_query; a fused
    pass at the analysis' scales), or None."""
    if args.query is None:
        return None
    query = int(merged.distinct_of([args.query])[0]) if merged is not None else args.query  # its distinct position
    dissimilarity = watch.watch(gls_filter('GLSMultiScaleDissimilarity', registrationName='Dissimilarity',
                                           Input=upstream, Normals=NORMALS, QueryPointId=query,
                                           NumberOfScales=args.scales,
                                           **scale_range(args, PriorMinScale=args.min_scale,
                                                         PriorMaxScale=args.max_scale)),
                                'dissimilarity')
    watch.update(dissimilarity)
    return gls_io.output_of(dissimilarity).GetPointData().GetArray('GLSDissimilarity')


def analyze(args, outputs):
    """Runs every stage, writing into `outputs`' staging folder; raises InputError, StageError or AnalysisError."""
    from paraview import simple
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkCommonCore import vtkLogger
    vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_WARNING)  # no INFO lines of VTK's own filters (the cutter)
    # A file whose header announces its point count (PLY, LAS, PCD) is checked against the memory before it is read
    # (a 10^8-point file takes minutes to read); every file is checked again once read, with its distinct points.
    announced = gls_io.announced_point_count(args.input)
    if announced:
        check_query(args, announced)
        gls_memory.check(announced, args.scales, args.per_scale, args.memory_budget, announced=True,
                         directions=not args.no_directions)
    simple.LoadPlugin(args.plugin, remote=False, ns=globals())
    watch = gls_watch.Watch()
    watch.handle_interruptions()
    source, data, description = gls_io.open_cloud(args.input, gls_filter, watch)
    count = data.GetNumberOfPoints()
    merged = gls_coincident.merge(data)
    non_finite = merged.non_finite if merged is not None else 0
    print('input: %s (%d points%s; %s)' % (
        args.input, count, '' if non_finite == 0 else ', %d of them with a non-finite coordinate (missing returns): '
        'left out, NaN results in their rows' % non_finite, description))
    check_query(args, count, merged)
    if merged is not None:
        if merged.note():
            print(merged.note())
        # The reader's references: `data` keeps the file's other arrays, not its positions.
        gls_io.release_output(source)
        source = gls_cloud.producer(merged.polydata)
    analysed = merged.polydata if merged is not None else data
    if analysed.GetNumberOfPoints() == 0:
        raise gls_io.InputError('%s: none of its %d points has finite coordinates: nothing to analyse'
                                % (args.input, count))
    if analysed.GetNumberOfPoints() < 2:
        raise gls_io.InputError('%s: all %d points are at one position: nothing to analyse' % (args.input, count))
    needed, budget = gls_memory.check(analysed.GetNumberOfPoints(), args.scales, args.per_scale, args.memory_budget,
                                      directions=not args.no_directions)
    print('memory: about %.1f GiB needed%s' % (needed / gls_memory.GIB, '' if budget is None else
                                              ' (%.1f GiB %s)' % (budget / gls_memory.GIB, 'budget' if
                                                                  args.memory_budget is not None else 'available')))

    start = time.time()
    upstream = source
    if not gls_cloud.has_normals(analysed):
        # The side each normal faces: what the file says (GLS Normal Estimation's Automatic rule, docs/normals.md),
        # or --orientation.
        upstream = watch.watch(gls_filter('GLSNormalEstimation', registrationName='Normals', Input=source,
                                          OutputPrecision='Single',
                                          MemoryBudget=gls_memory.filter_budget_mib(budget),
                                          **orientation_properties(args, analysed)),
                               'normals')
        watch.update(upstream)
        how = gls_io.output_of(upstream).GetFieldData().GetAbstractArray('GLSOrientation')
        print('normals: %.2f s; oriented %s' % (time.time() - start, how.GetValue(0) if how is not None else '?'))
    elif args.orientation != 'auto':
        print('normals: the file\'s own (--orientation applies to estimated normals only)')
    features = (per_scale_pipeline if args.per_scale else summary_pipeline)(args, upstream, watch, budget)
    watch.update(features)
    result = gls_io.output_of(features)
    tiles = result.GetFieldData().GetArray('GLSTiles')
    if tiles is not None:
        print('features and summary: in %d spatial tiles, one after the other, to stay within the memory budget'
              % tiles.GetValue(0))
    feature = checked_features(result)
    elapsed = time.time() - start
    pd = result.GetPointData()
    scales = vtk_to_numpy(result.GetFieldData().GetArray('GLSScales')).copy()
    minimum_neighbours = int(result.GetFieldData().GetArray('GLSMinimumNeighbors').GetValue(0))
    print('GLS pipeline: %.2f s; %d scales from %.4g to %.4g (length units of the data); feature in [%.3f, %.3f], '
          'median %.3f' % (elapsed, len(scales), scales[0], scales[-1], np.nanmin(feature), np.nanmax(feature),
                           np.nanmedian(feature)))
    dissimilarity = query_dissimilarity(args, upstream, watch, merged)
    if dissimilarity is not None:
        pd.AddArray(dissimilarity)
    report_directions(args, pd)

    picks = gls_profiles.select_profile_points(feature, vtk_to_numpy(pd.GetArray('GLSPertinentScaleCount')))
    if merged is not None:
        # The arrays of the fused pass (not the normals', which the profiles and the denoising read) go once copied.
        shared = gls_io.output_of(upstream).GetPointData()
        own = [pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays()) if not shared.HasArray(pd.GetArrayName(i))]
        output = merged.scatter(result, release=set(own))
    else:
        output = result
    if output.GetNumberOfCells() == 0:  # a cloud without cells: one poly-vertex, so that ParaView shows the .vtp
        output.SetVerts(gls_cloud.poly_vertex_cell(output.GetNumberOfPoints()))
    if not args.per_scale:
        output, narrowed = gls_outputs.compact(output, args.full_precision)
        print('output: per-point summaries in float32 (the filters write them so: OutputPrecision Single), the count '
              'in uint8; %s%s' % ('narrowed here: %s' % ', '.join(narrowed) if narrowed else 'none narrowed here',
                                  '' if args.full_precision else '; rounded to a relative 1.2e-4 (the normals '
                                  '7.6e-6): --full-precision keeps every bit'))
        # The features' arrays are not needed any more (the output holds their rounded copies, or shares them):
        # released before the writer's fork, whose copy of this process would keep them.
        del feature, pd
        result.Initialize()
        gls_io.release_output(features)
    # Written while the pictures are made (the .vtp compressed, the LAS and PLY files encoded), one process each.
    writing = [outputs.write_in_background(output_format, output) for output_format in args.output_format]
    pictures = [(outputs.path('-features.png'), gls_render.FEATURES,
                 'GLS continuous features: %s (%d points)' % (outputs.name, count - non_finite))]
    if not args.no_directions:
        pictures.append((outputs.path('-shape-index.png'), gls_render.SHAPE_INDEX,
                         'GLS shape index where the principal directions are steadiest: %s (%d points)'
                         % (outputs.name, count - non_finite)))
    gls_render.render_point_arrays(output, pictures)

    # The profiles' fits read the picked points' neighbourhoods only (at the analysis' scales, as lengths, with its
    # minimum neighbour count), summed exactly: a few points, whatever the cloud's size.
    neighbourhoods, crop_ids = gls_profiles.around(gls_io.output_of(upstream), picks.values(), scales[-1] * 1.001)
    profiles = watch.watch(gls_filter('GLSScaleProfiles', registrationName='Profiles',
                                      Input=gls_cloud.producer(neighbourhoods), Normals=NORMALS, PointIds=crop_ids,
                                      NumberOfScales=300, ScaleSampling='Quadratic', ScaleUnits='Absolute',
                                      MinScale=float(scales[0]), MaxScale=float(scales[-1]), Evaluation='Exact',
                                      MinimumNeighbors=minimum_neighbours),
                           'scale profiles', progress=False)
    watch.update(profiles)
    gls_profiles.plot_profiles(outputs.path('-profiles.png'), 'GLS scale profiles: %s' % outputs.name,
                               gls_io.output_of(profiles), picks, dict(zip(picks.keys(), crop_ids)))

    cloud = analysed if upstream is source else gls_io.output_of(upstream)
    stage = gls_denoising.denoise(gls_filter, cloud, args.noise, watch)
    rms = gls_denoising.offsets(stage)
    print('denoising: %.2f s%s; bandwidth searched from %.4g to %.4g; RMS distance to the input surface %.4g -> %.4g'
          % (stage['seconds'], gls_denoising.sample_note(stage), gls_denoising.MIN_BANDWIDTH * stage['spacing'],
             gls_denoising.MAX_BANDWIDTH * stage['spacing'], rms['noisy'], rms['denoised']))
    gls_denoising.render(outputs.path('-denoising.png'), stage,
                         'GLS denoising: %s%s%s (left) -> adaptive-bandwidth MLS projection (right)'
                         % (outputs.name, ' + noise %.3g x diagonal' % args.noise if args.noise > 0 else '',
                            gls_denoising.sample_note(stage)))

    curve, axis = gls_cross_section.longest_section(analysed)
    if curve is None:
        print('scale-space image: skipped (the input has no polygons to cut a cross-section from)')
    else:
        image, crossings = gls_cross_section.scale_space_image(gls_filter, curve, watch)
        gls_cross_section.plot(outputs.path('-scale-space.png'),
                               'GLS scale-space image of the central cross-section of %s (%d points)'
                               % (outputs.name, curve.GetNumberOfPoints()), curve, axis, image, crossings)
    for write in writing:
        write.finish()
        print('wrote the data (%s): %.1f bytes per point' % (os.path.splitext(write.path)[1][1:],
                                                             os.path.getsize(write.path) / float(count)))
    if 'vtp' in args.output_format:
        vtp = writing[args.output_format.index('vtp')]
        gls_outputs.save_state(outputs.path('-gls.pvsm'), vtp.path, outputs.final('-gls.vtp'), output)


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
        written = outputs.commit()
    except (gls_io.InputError, gls_watch.StageError, gls_memory.BudgetError, AnalysisError,
            gls_outputs.OutputError) as e:
        outputs.discard()
        return fail('%s; no results written' % e)
    except OSError as e:  # a picture, the state or a move failed: a full disk, a quota, a read-only folder
        outputs.discard()
        elsewhere = e.filename and not os.path.abspath(str(e.filename)).startswith(os.path.abspath(args.output_dir))
        if elsewhere:  # not one of the results (no stage writes elsewhere: a file it reads)
            return fail('%s: %s; no results written' % (e.filename, e.strerror or e))
        return fail('cannot write the results in %s: %s%s; no results written' % (
            args.output_dir, e.strerror or e, ' (%s)' % os.path.basename(e.filename) if e.filename else ''))
    except (gls_watch.Interrupted, KeyboardInterrupt):
        outputs.discard()
        return fail('interrupted; no results written', 130)
    except BaseException as e:
        outputs.discard()
        if isinstance(e, SystemExit):
            raise
        traceback.print_exc()
        return fail('internal error (the traceback above); no results written', 1)
    for path in written:
        print('wrote %s' % path)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
