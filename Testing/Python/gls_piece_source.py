"""A point cloud made from a scan that honours ParaView's piece requests, for the MPI test and the MPI throughput
benchmark: a ProgrammableSource that every rank runs. Each rank reads the scan (an OBJ), keeps every `stride`-th
vertex (file order), lays `copies` of that cloud side by side along x (1.05 times its width apart), numbers the
points with a GlobalIds attribute (their serial index) and keeps the slab of x it owns (the points sorted by x, cut
in N equal counts; one rank: the whole cloud in serial order). With `all_on_rank0`, rank 0 keeps the whole cloud
and the other ranks get empty pieces (what a reader that ignores pieces gives). With `stray`, one more point (the
last id) lies far from the rest, 10 times the cloud's largest extent beyond its upper corner (in the last slab): a
stray return every filter must leave out on every piece layout as the serial run does."""

SCRIPT = r'''
import numpy as np
from vtkmodules.vtkIOGeometry import vtkOBJReader
from vtkmodules.vtkCommonDataModel import vtkCellArray
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as sddp
from vtkmodules.util.numpy_support import vtk_to_numpy, numpy_to_vtk, numpy_to_vtkIdTypeArray
info = self.GetOutputInformation(0)
piece = info.Get(sddp.UPDATE_PIECE_NUMBER()) if info.Has(sddp.UPDATE_PIECE_NUMBER()) else 0
pieces = info.Get(sddp.UPDATE_NUMBER_OF_PIECES()) if info.Has(sddp.UPDATE_NUMBER_OF_PIECES()) else 1
reader = vtkOBJReader()
reader.SetFileName(SCAN)
reader.Update()
one = vtk_to_numpy(reader.GetOutput().GetPoints().GetData()).astype(np.float64)[::STRIDE]
width = 1.05 * (one[:, 0].max() - one[:, 0].min())
xyz = np.concatenate([one + np.array([c * width, 0.0, 0.0]) for c in range(COPIES)])
if STRAY:
    low, high = xyz.min(axis=0), xyz.max(axis=0)
    xyz = np.concatenate([xyz, [high + 10.0 * (high - low).max()]])
ids = np.arange(len(xyz), dtype=np.int64)
order = np.argsort(xyz[:, 0], kind='stable')
mine = np.sort(np.array_split(order, pieces)[piece])
if ALL_ON_RANK0:
    mine = ids if piece == 0 else ids[:0]
out = self.GetPolyDataOutput()
pts = vtkPoints()
pts.SetData(numpy_to_vtk(np.ascontiguousarray(xyz[mine]), deep=1))
out.SetPoints(pts)
verts = vtkCellArray()
verts.SetData(numpy_to_vtkIdTypeArray(np.arange(len(mine) + 1, dtype=np.int64), deep=1),
              numpy_to_vtkIdTypeArray(np.arange(len(mine), dtype=np.int64), deep=1))
out.SetVerts(verts)
gid = numpy_to_vtkIdTypeArray(np.ascontiguousarray(ids[mine]), deep=1)
gid.SetName('GlobalIds')
out.GetPointData().SetGlobalIds(gid)
'''

INFO_SCRIPT = r'''
from vtkmodules.vtkCommonExecutionModel import vtkAlgorithm
self.GetOutputInformation(0).Set(vtkAlgorithm.CAN_HANDLE_PIECE_REQUEST(), 1)
'''


def piece_source(scan, stride=1, copies=1, all_on_rank0=False, stray=False):
    """The ProgrammableSource proxy described above."""
    from paraview import simple
    script = SCRIPT.replace('SCAN', repr(scan)).replace('STRIDE', str(stride)).replace(
        'COPIES', str(copies)).replace('ALL_ON_RANK0', str(bool(all_on_rank0))).replace('STRAY', str(bool(stray)))
    return simple.ProgrammableSource(OutputDataSetType='vtkPolyData', Script=script,
                                     ScriptRequestInformation=INFO_SCRIPT)
