"""The GLS pipeline on the bundled scan, run by pvbatch on one or several MPI ranks; saves every GLS array (ordered by
global point id) to an .npz file for run_mpi_compare.py.

    [mpiexec -np N] pvbatch mpi_pipeline.py <plugin.so> <scan.obj> <out.npz> [--stride S] [--all-on-rank0]
        [--memory-budget MIB FEATURES_MIB]
    pvpython mpi_pipeline.py ... --server HOST:PORT     (a pvserver started with mpiexec -np N pvserver)

The cloud comes from gls_piece_source (a programmable source that honours ParaView's piece requests): every S-th
vertex of the scan and one stray point far from it (every filter leaves it out: NaN results and the bounds of the
rest, GLSStray marking it), numbered with GlobalIds, one slab of x per rank; with --all-on-rank0, all of it on rank 0 and
empty pieces elsewhere. The pipeline: oriented normals (minimum spanning tree) -> scale space -> geometric
variation -> continuous features -> dissimilarity to a point id (these three reuse the stored scale space), and,
fitting themselves from the normals: geometric variation, continuous features, dissimilarity to a point given by its
coordinates; normals re-estimated over a radius and made to agree with the first ones; the MLS projection (moved
points); the adaptive bandwidth and the projection with it; the scale profiles of three points (a table,
assembled on rank 0). Also saved per point: the rank that computed it and how many ghost points that rank used.
The scale-space image of a closed curve from a source that ignores pieces (all on rank 0). And, for a serial-only
filter (normal estimation of a planar input), the size of its output (on several processes it must refuse to run:
an empty output).
"""
import argparse
import os
import sys

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from vtkmodules.util.numpy_support import vtk_to_numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gls_piece_source import piece_source  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument('plugin')
parser.add_argument('scan')
parser.add_argument('out')
parser.add_argument('--stride', type=int, default=3)
parser.add_argument('--all-on-rank0', action='store_true')
parser.add_argument('--server', help='HOST:PORT of a running pvserver (the pipeline then runs on its ranks)')
parser.add_argument('--memory-budget', type=float, nargs=2, default=[0.0, 0.0], metavar=('MIB', 'FEATURES_MIB'),
                    help='MemoryBudget (MiB) of the fused filters, and of the continuous features (which also hold '
                         'their relative sigma\'s sample of nu): tight ones cut their fits into spatial tiles')
args = parser.parse_args()

if args.server:
    host, port = args.server.rsplit(':', 1)
    Connect(host, int(port))  # noqa: F405
LoadPlugin(args.plugin, remote=bool(args.server), ns=globals())

# Per point: the rank that computed it, the ghost points that rank's fit used (field data GLSGhostPoints) and the
# spatial tiles it was cut into (GLSTiles).
TAG_SCRIPT = r'''
import numpy as np
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.util.numpy_support import numpy_to_vtk
inp = self.GetInput()
out = self.GetOutput()
out.ShallowCopy(inp)
n = inp.GetNumberOfPoints()
c = vtkMultiProcessController.GetGlobalController()
rank = c.GetLocalProcessId() if c else 0
g = inp.GetFieldData().GetArray('GLSGhostPoints')
ghosts = g.GetValue(0) if g else 0
t = inp.GetFieldData().GetArray('GLSTiles')
tiles = t.GetValue(0) if t else 1
for name, value in (('Rank', rank), ('GhostsOnRank', ghosts), ('TilesOnRank', tiles)):
    a = numpy_to_vtk(np.full(n, value, dtype=np.float64), deep=1)
    a.SetName(name)
    out.GetPointData().AddArray(a)
'''

scales = dict(MinScale=0.01, MaxScale=0.06, NumberOfScales=6, ScaleSampling='Quadratic')
cloud = piece_source(args.scan, stride=args.stride, all_on_rank0=args.all_on_rank0, stray=True)
normals = GLSNormalEstimation(Input=cloud, NumberOfNeighbors=16, Orientation='Minimum spanning tree')  # noqa: F405
space = GLSScaleSpace(Input=normals, **scales)  # noqa: F405
variation = GLSGeometricVariation(Input=space)  # noqa: F405
features = GLSContinuousFeatures(Input=variation)  # noqa: F405
similar = GLSMultiScaleDissimilarity(Input=features, QueryPointId=1234, PriorMinScale=0.02)  # noqa: F405
fused_variation = GLSGeometricVariation(Input=normals, **scales)  # noqa: F405
tagged = ProgrammableFilter(Input=fused_variation, OutputDataSetType='vtkPolyData', Script=TAG_SCRIPT)  # noqa: F405
# The fused features at smaller scales than the rest: a rank's piece is then several bands of the largest scale wide,
# so that its fit can be cut into tiles smaller than itself (--memory-budget; each tile holds its band besides).
feature_scales = dict(scales, MaxScale=0.04)
fused_features = GLSContinuousFeatures(Input=normals, **feature_scales)  # noqa: F405
tagged_features = ProgrammableFilter(Input=fused_features, OutputDataSetType='vtkPolyData',  # noqa: F405
                                     Script=TAG_SCRIPT)
fused_similar = GLSMultiScaleDissimilarity(Input=normals, UseQueryPointCoordinates=1,  # noqa: F405
                                           QueryPoint=[-0.03, 0.12, 0.03], PriorMinScale=0.02, **scales)
agreeing = GLSNormalEstimation(Input=normals, NeighborhoodType='Radius', Radius=0.006,  # noqa: F405
                               Orientation='Agree with existing normals', ExistingNormals=['POINTS', 'Normals'])
refined = GLSNormalEstimation(Input=cloud, NumberOfNeighbors=16, Refinement='GLS')  # noqa: F405
projection = GLSProjection(Input=normals, ScaleMode='Fixed scale', Scale=0.02)  # noqa: F405
bandwidth = GLSAdaptiveBandwidth(Input=normals, MinScale=0.005, MaxScale=0.03, NumberOfScales=8,  # noqa: F405
                                 ScaleSampling='Logarithmic', SmoothingRadius=0.02)
adaptive = GLSProjection(Input=bandwidth)  # noqa: F405  (the per-point GLSBandwidth)
# The multi-resolution evaluation (forced: the bunny is below Auto's limit), whose cells reach past the largest scale.
cells_space = GLSScaleSpace(Input=normals, Evaluation='Multiresolution', Accuracy=0.3, **scales)  # noqa: F405
cells_features = GLSContinuousFeatures(Input=normals, Evaluation='Multiresolution', **feature_scales)  # noqa: F405
# The principal curvatures: stored at every scale, and the steadiest directions (fused).
curvature_space = GLSScaleSpace(Input=normals, StorePrincipalCurvatures=1, **scales)  # noqa: F405
directions = GLSPrincipalDirections(Input=normals, **scales)  # noqa: F405
# The main job's fused pass: the features, their summary and the steadiest directions from one fit (untiled: the
# tiled run's budgets are the features pass's).
summary_directions = GLSContinuousFeatures(Input=normals, ScaleSummary=1, DirectionSummary=1,  # noqa: F405
                                           **feature_scales)
for fused in (fused_variation, fused_similar):
    fused.MemoryBudget = args.memory_budget[0]
for fused in (fused_features, cells_features):
    fused.MemoryBudget = args.memory_budget[1]

saved = {}
for prefix, proxy in (('chain', similar), ('fused_variation', tagged), ('fused_features', tagged_features),
                      ('fused_similar', fused_similar), ('radius_agreeing', agreeing), ('refined', refined),
                      ('projection', projection), ('adaptive_projection', adaptive), ('cells_space', cells_space),
                      ('cells_features', cells_features), ('curvature_space', curvature_space),
                      ('principal_directions', directions), ('summary_directions', summary_directions)):
    proxy.UpdatePipeline()
    data = servermanager.Fetch(proxy)
    pd = data.GetPointData()
    gid = vtk_to_numpy(pd.GetArray('GlobalIds')).astype(np.int64)
    order = np.argsort(gid)
    saved[prefix + '/GlobalIds'] = gid[order]
    saved[prefix + '/Points'] = vtk_to_numpy(data.GetPoints().GetData()).astype(np.float64)[order]
    for i in range(pd.GetNumberOfArrays()):
        name = pd.GetArrayName(i)
        if name and name != 'GlobalIds':
            saved[prefix + '/' + name] = vtk_to_numpy(pd.GetArray(i)).astype(np.float64)[order]
    query = data.GetFieldData().GetArray('GLSQueryPointId')
    if query is not None:
        saved[prefix + '/GLSQueryPointId'] = np.array([query.GetValue(0)], dtype=np.float64)
# Scale profiles of three points (global ids), compared column by column.
profiles = GLSScaleProfiles(Input=normals, PointIds=[5, 6000, 11000], NumberOfScales=10)  # noqa: F405
profiles.UpdatePipeline()
table = servermanager.Fetch(profiles)
for i in range(table.GetNumberOfColumns()):
    saved['profiles/' + table.GetColumnName(i)] = vtk_to_numpy(table.GetColumn(i)).astype(np.float64)
# A curve (a source that ignores pieces: all of it on rank 0): its scale-space image, computed on the rank holding
# it, compared value by value; and a serial-only filter, normal estimation of a planar input: its output size (0
# when it refused to run on several processes).
theta = 2 * np.pi * np.arange(300) / 300
radius = 1 + 0.25 * np.cos(5 * theta)
flower = PolyLineSource(Closed=1, Points=np.stack([radius * np.cos(theta), radius * np.sin(theta),  # noqa: F405
                                                   0 * theta], axis=1).ravel().tolist())
image = GLSScaleSpaceImage(Input=flower, ScaleUnits='Absolute', MinScale=0.05, MaxScale=1.0,  # noqa: F405
                           NumberOfScales=20, NumberOfArclengthSamples=200)
image.UpdatePipeline()
picture = servermanager.Fetch(image, idx=0)
saved['image/Dimensions'] = np.array(picture.GetDimensions(), dtype=np.float64)
for name in ('GLSKappa', 'GLSNu'):
    array = picture.GetPointData().GetArray(name)
    saved['image/' + name] = vtk_to_numpy(array).astype(np.float64) if array else np.zeros(0)
planar = GLSNormalEstimation(Input=flower, NumberOfNeighbors=8)  # noqa: F405
planar.UpdatePipeline()
computed = servermanager.Fetch(planar).GetPointData().GetArray('Normals')
saved['serial_only/PlanarNormalEstimationPoints'] = np.array([computed.GetNumberOfTuples() if computed else 0],
                                                             dtype=np.float64)
np.savez(args.out, **saved)
print('saved %d arrays of %d points to %s' % (len(saved), len(saved['chain/GlobalIds']), args.out))

