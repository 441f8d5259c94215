"""Throughput of the distributed GLS filters in pvbatch (the scaling note of docs/distributed.md).

    [mpiexec -np N] pvbatch mpi_throughput.py <plugin.so> <scan.obj> [--copies C] [--threads T] [--scales S]
        [--orientation 'Minimum spanning tree' | 'Towards point' | ...]

The cloud: C copies of the scan side by side along x (a strip of constant density, like a survey), cut into N
slabs of x by Testing/Python/gls_piece_source (a programmable source that honours ParaView's piece requests:
every rank builds it and keeps its slab). Scales are absolute: 0.8% to 8% of one copy's diagonal (S quadratic scales, default 20), so the ghost band
does not grow with the cloud. Times, on rank 0 (wall clock, every rank working): normal estimation (16 nearest,
minimum spanning tree, gathered on rank 0), the scale space (every array stored) and the fused continuous features;
then every rank's owned and ghost points (the scale space's field data GLSGhostPoints).
Each filter runs on T threads per rank (default 1: N ranks = N cores).
"""
import argparse
import os
import sys
import time

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'Python'))
from gls_piece_source import piece_source  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument('plugin')
parser.add_argument('scan')
parser.add_argument('--copies', type=int, default=5)
parser.add_argument('--threads', type=int, default=1)
parser.add_argument('--scales', type=int, default=20)
parser.add_argument('--orientation', default='Minimum spanning tree')
args = parser.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())

cloud = piece_source(args.scan, copies=args.copies)
cloud.UpdatePipeline()
n = cloud.GetDataInformation().GetNumberOfPoints()
# One copy's bounding-box diagonal is about 0.25 (the bunny: 0.155 x 0.154 x 0.120).
scales = dict(ScaleUnits='Absolute', MinScale=0.008 * 0.25, MaxScale=0.08 * 0.25, NumberOfScales=args.scales,
              ScaleSampling='Quadratic', NumberOfThreads=args.threads)
normals = GLSNormalEstimation(Input=cloud, NumberOfNeighbors=16, Orientation=args.orientation,  # noqa: F405
                              OrientationPoint=[0.0, 1.0, 1.0], NumberOfThreads=args.threads)
space = GLSScaleSpace(Input=normals, **scales)  # noqa: F405
features = GLSContinuousFeatures(Input=normals, **scales)  # noqa: F405
ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
print('%d points, %d ranks x %d threads, %d scales, orientation: %s' % (n, ranks, args.threads, args.scales,
                                                                       args.orientation))
for label, proxy in (('normal estimation', normals), ('scale space', space), ('continuous features', features)):
    start = time.perf_counter()
    proxy.UpdatePipeline()
    seconds = time.perf_counter() - start
    print('%-20s %7.2f s  %9.0f points/s' % (label, seconds, n / seconds))

# One point per rank carrying its owned and ghost point counts.
COUNT_SCRIPT = r'''
from vtkmodules.vtkCommonCore import vtkPoints, vtkDoubleArray
inp = self.GetInput()
out = self.GetOutput()
pts = vtkPoints()
pts.InsertNextPoint(0.0, 0.0, 0.0)
out.SetPoints(pts)
g = inp.GetFieldData().GetArray('GLSGhostPoints')
for name, value in (('owned', inp.GetNumberOfPoints()), ('ghosts', g.GetValue(0) if g else 0)):
    a = vtkDoubleArray()
    a.SetName(name)
    a.InsertNextValue(value)
    out.GetPointData().AddArray(a)
'''
counts = servermanager.Fetch(ProgrammableFilter(Input=space, OutputDataSetType='vtkPolyData',  # noqa: F405
                                                Script=COUNT_SCRIPT))
for r in range(counts.GetNumberOfPoints()):
    owned = counts.GetPointData().GetArray('owned').GetValue(r)
    ghosts = counts.GetPointData().GetArray('ghosts').GetValue(r)
    share = 100.0 * ghosts / (owned if owned > 0 else 1.0)
    print('piece %d: %d owned points, %d ghost points (%.1f%%)' % (r, owned, ghosts, share))
