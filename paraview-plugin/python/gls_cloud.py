"""vtkPolyData helpers of the main job: vertex cells, a vertex cloud from numpy arrays, whether a dataset has
normals, and a ParaView source proxy serving a polydata."""
import numpy as np


def vertex_cells(count):
    """A vtkCellArray with one vertex cell per point (offsets 0..count, connectivity 0..count-1)."""
    from vtkmodules.util.numpy_support import numpy_to_vtkIdTypeArray
    from vtkmodules.vtkCommonDataModel import vtkCellArray
    cells = vtkCellArray()
    cells.SetData(numpy_to_vtkIdTypeArray(np.arange(count + 1, dtype=np.int64), deep=True),
                  numpy_to_vtkIdTypeArray(np.arange(count, dtype=np.int64), deep=True))
    return cells


def poly_vertex_cell(count):
    """A vtkCellArray with one poly-vertex cell of all `count` points: what shows a cloud without cells in ParaView
    at 4 bytes a point in a file (ids written as int32), where a vertex cell per point takes 16."""
    from vtkmodules.util.numpy_support import numpy_to_vtkIdTypeArray
    from vtkmodules.vtkCommonDataModel import vtkCellArray
    cells = vtkCellArray()
    cells.SetData(numpy_to_vtkIdTypeArray(np.array([0, count], dtype=np.int64), deep=True),
                  numpy_to_vtkIdTypeArray(np.arange(count, dtype=np.int64), deep=True))
    return cells


def stride_for(count, limit):
    """The smallest k such that every k-th of `count` points is at most `limit` points."""
    return max(1, -(-count // limit))


def every_kth_note(k):
    """'every k-th point' in words ('every 2nd point', 'every 20th point')."""
    return 'every %d%s point' % (k, {2: 'nd', 3: 'rd'}.get(k, 'th'))


def vertex_cloud(points, arrays):
    """A polydata of `points` (n x 3) with one vertex cell each and the point arrays `arrays` ({name: values});
    the first array is the active scalars."""
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    pd = vtkPolyData()
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(points, dtype=float), deep=True))
    pd.SetPoints(pts)
    pd.SetVerts(vertex_cells(len(points)))
    for i, (name, values) in enumerate(arrays.items()):
        array = numpy_to_vtk(np.ascontiguousarray(values), deep=True)
        array.SetName(name)
        pd.GetPointData().AddArray(array)
        if i == 0:
            pd.GetPointData().SetActiveScalars(name)
    return pd


def has_surface(polydata):
    return polydata.GetNumberOfPolys() + polydata.GetNumberOfStrips() > 0


def has_normals(polydata):
    """Whether the dataset has a floating-point 3-component point array named Normals."""
    normals = polydata.GetPointData().GetArray('Normals')
    return normals is not None and normals.GetNumberOfComponents() == 3 and normals.GetDataTypeAsString() in (
        'float', 'double')


def producer(polydata):
    """A ParaView source proxy (TrivialProducer) serving `polydata`."""
    from paraview import simple
    source = simple.TrivialProducer()
    source.GetClientSideObject().SetOutput(polydata)
    return source
