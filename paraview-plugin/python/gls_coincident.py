"""Coincident points for the main job: a mesh whose vertices are split per face corner (OBJ files with texture
coordinates: ParaView's reader gives spot.obj's 2,930 vertices as 17,568 points) holds several points at exactly the
same position. The main job analyses each position once and writes the results back to every copy:

  merge(polydata)          -> Merged (the distinct positions, first copies first, with the cells renumbered and
                              the normals of the copies averaged), or None when no two points coincide
  Merged.scatter(result)   -> the input again (every point, cell and array of the file), with the arrays the
                              analysis added to `result` copied to every copy of each position

Coincident means equal coordinates (so 0.0 and -0.0 coincide, NaN coordinates never do). The normals of a merged
position are the normalized mean of its copies' unit normals (NaN when they cancel, so the GLS filters leave that
position out)."""
import numpy as np


class Merged:
    """The distinct positions of a cloud (`polydata`) and the map back to the input's points (`inverse`)."""

    def __init__(self, source, polydata, inverse):
        self.source = source
        self.polydata = polydata
        self.inverse = inverse
        self.copies = source.GetNumberOfPoints() - polydata.GetNumberOfPoints()

    def note(self):
        return ('note: %d of the %d points coincide with an earlier one; the analysis runs on the %d distinct '
                'positions and writes the results back to every copy'
                % (self.copies, self.source.GetNumberOfPoints(), self.polydata.GetNumberOfPoints()))

    def scatter(self, result):
        """The input polydata with every point array of `result` (on the merged points) that the input lacks,
        and `result`'s field data, copied to every copy of each position."""
        from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
        from vtkmodules.vtkCommonDataModel import vtkPolyData
        out = vtkPolyData()
        out.ShallowCopy(self.source)
        arrays = result.GetPointData()
        for i in range(arrays.GetNumberOfArrays()):
            array = arrays.GetArray(i)
            if array is None or out.GetPointData().HasArray(array.GetName()):
                continue
            values = vtk_to_numpy(array)[self.inverse]
            copy = numpy_to_vtk(np.ascontiguousarray(values), deep=True, array_type=array.GetDataType())
            copy.SetName(array.GetName())
            for c in range(array.GetNumberOfComponents()):
                if array.GetComponentName(c):
                    copy.SetComponentName(c, array.GetComponentName(c))
            out.GetPointData().AddArray(copy)
        if out.GetPointData().GetNormals() is None and out.GetPointData().HasArray('Normals'):
            out.GetPointData().SetActiveNormals('Normals')
        for i in range(result.GetFieldData().GetNumberOfArrays()):
            out.GetFieldData().AddArray(result.GetFieldData().GetAbstractArray(i))
        return out


def distinct_positions(points):
    """(first, inverse): the index of the first copy of each distinct row of `points`, in order of appearance,
    and for every row the index of its distinct position."""
    _, first, inverse = np.unique(points, axis=0, return_index=True, return_inverse=True)
    order = np.argsort(first, kind='stable')
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    return first[order], rank[inverse.reshape(-1)]


def merged_normals(normals, inverse, count):
    """The normalized mean of the unit normals of each position's copies (NaN where they cancel)."""
    lengths = np.linalg.norm(normals, axis=1)
    with np.errstate(invalid='ignore', divide='ignore'):
        unit = np.where(lengths[:, None] > 0, normals / lengths[:, None], np.nan)
    sums = np.zeros((count, 3))
    np.add.at(sums, inverse, unit)
    norms = np.linalg.norm(sums, axis=1)
    with np.errstate(invalid='ignore', divide='ignore'):
        return np.where(norms[:, None] > 1e-9, sums / norms[:, None], np.nan)


def renumbered_cells(cells, inverse):
    """A copy of a vtkCellArray with every point id replaced by its distinct position's."""
    from vtkmodules.util.numpy_support import numpy_to_vtkIdTypeArray, vtk_to_numpy
    from vtkmodules.vtkCommonDataModel import vtkCellArray
    out = vtkCellArray()
    if cells.GetNumberOfCells() == 0:
        return out
    offsets = vtk_to_numpy(cells.GetOffsetsArray()).astype(np.int64)
    connectivity = inverse[vtk_to_numpy(cells.GetConnectivityArray()).astype(np.int64)].astype(np.int64)
    out.SetData(numpy_to_vtkIdTypeArray(np.ascontiguousarray(offsets), deep=True),
                numpy_to_vtkIdTypeArray(np.ascontiguousarray(connectivity), deep=True))
    return out


def merge(polydata):
    """A Merged view of `polydata`, or None when no two of its points coincide."""
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    points = vtk_to_numpy(polydata.GetPoints().GetData()).astype(float)
    first, inverse = distinct_positions(points)
    if len(first) == len(points):
        return None
    merged = vtkPolyData()
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(points[first]), deep=True))
    merged.SetPoints(pts)
    merged.SetVerts(renumbered_cells(polydata.GetVerts(), inverse))
    merged.SetLines(renumbered_cells(polydata.GetLines(), inverse))
    merged.SetPolys(renumbered_cells(polydata.GetPolys(), inverse))
    merged.SetStrips(renumbered_cells(polydata.GetStrips(), inverse))
    normals = polydata.GetPointData().GetArray('Normals')
    if normals is not None and normals.GetNumberOfComponents() == 3:
        averaged = numpy_to_vtk(merged_normals(vtk_to_numpy(normals).astype(float), inverse, len(first)), deep=True)
        averaged.SetName('Normals')
        merged.GetPointData().SetNormals(averaged)
    return Merged(polydata, merged, inverse)
