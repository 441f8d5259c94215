"""The positions the main job analyses: each distinct finite position once. A mesh whose vertices are split per face
corner (OBJ files with texture coordinates: ParaView's reader gives spot.obj's 2,930 vertices as 17,568 points) holds
several points at exactly the same position; an organized scan (a depth camera's PCD, 640 x 480) holds rows of NaN
for its missing returns. The main job analyses each finite position once and writes the results back to every row:

  merge(polydata)          -> Merged (the distinct finite positions, first copies first, with the cells renumbered
                              (a cell with a point left out is left out), the normals of the copies averaged, the
                              CARRIED_ARRAYS of the first copies and the field data of the file), or
                              None when no two points coincide and every point is finite; the input's own positions
                              are released meanwhile (a second copy of every position: 1.2 GB at 10^8 float points),
                              and only the other rows (later copies, non-finite rows) are kept, with their distinct
                              positions (the map from every point to its distinct position is formed when needed:
                              0.4 GB less held through the analysis at 10^8 points)
  Merged.scatter(result)   -> the input again (every point, cell and array of the file, in the file's order: an
                              organized cloud keeps its rows and columns), with the arrays the analysis added to
                              `result` copied to every copy of each position; a non-finite row gets NaN (0 in an
                              integer array) and NaN coordinates (an infinite coordinate too, so that no bound holds
                              an infinity), the other positions are rebuilt bit for bit

Coincident means equal coordinates (so 0.0 and -0.0 coincide). A row with a NaN or infinite coordinate is left out
(`non_finite` counts them). The normals of a merged position are the normalized mean of its copies' unit normals (NaN
when they cancel, so the GLS filters leave that position out)."""
import numpy as np

# The point arrays the analysis reads besides the positions and normals, carried to the analysed positions (each
# position's first copy's values): the scanner positions and the lidar attributes from which GLS Normal Estimation's
# Automatic orientation decides (vtkGLSNormalEstimation.h).
CARRIED_ARRAYS = ('ScannerPosition', 'ScanAngle', 'NumberOfReturns', 'Classification')


class Merged:
    """The distinct finite positions of a cloud (`polydata`) and the map back to the input's points (`distinct_of`,
    `inverse`: -1 for a row left out)."""

    def __init__(self, source, polydata, copy_rows, copy_targets, copy_points):
        """`source`'s positions are released: each point's is its distinct position's (`polydata`'s: the k-th first
        copy's is the k-th), but for the rows `copy_rows` (the later copies and the non-finite rows, increasing),
        whose distinct positions are `copy_targets` (-1: a non-finite row) and own bits `copy_points` (a copy's are
        equal as floats, they may differ in bits: -0.0 and 0.0)."""
        self.source = source
        self.polydata = polydata
        self.count = source.GetNumberOfPoints()
        self.non_finite = int(np.count_nonzero(copy_targets < 0))
        self.copies = self.count - polydata.GetNumberOfPoints() - self.non_finite
        self.copy_rows = copy_rows
        self.copy_targets = copy_targets
        self.copy_points = copy_points
        source.SetPoints(None)

    def distinct_of(self, rows):
        """The distinct position of each input point in `rows` (an array of indices): a first copy's is its rank
        among the first copies (its index less the other rows before it); -1 for a non-finite row."""
        rows = np.asarray(rows, dtype=np.int64)
        before = np.searchsorted(self.copy_rows, rows)
        out = rows - before
        at = np.minimum(before, max(len(self.copy_rows) - 1, 0))
        later = self.copy_rows[at] == rows if len(self.copy_rows) else np.zeros(len(rows), dtype=bool)
        out[later] = self.copy_targets[at[later]]
        return out

    def inverse(self, chunk=1 << 22):
        """distinct_of every input point (32 bits where they fit), `chunk` points at a time."""
        out = np.empty(self.count, dtype=np.int32 if self.count < 2 ** 31 else np.int64)
        for start in range(0, self.count, chunk):
            out[start:start + chunk] = self.distinct_of(np.arange(start, min(start + chunk, self.count)))
        return out

    def left_out_rows(self):
        """The rows left out of the analysis (a non-finite coordinate), increasing."""
        return self.copy_rows[self.copy_targets < 0]

    def note(self):
        """The note on the coincident points for the main job's log ('' when none coincide; the non-finite rows
        are counted in its input line)."""
        if self.copies == 0:
            return ''
        return ('note: %d of the %d points coincide with an earlier one; the analysis runs on the %d distinct '
                'positions and writes the results back to every copy'
                % (self.copies, self.count, self.polydata.GetNumberOfPoints()))

    def source_points(self, inverse=None):
        """The input's positions (vtkPoints in the input's type), rebuilt from the distinct ones bit for bit, and
        NaN in the three coordinates of a non-finite row (`inverse`: the map of inverse(), when the caller has formed
        it already)."""
        from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
        from vtkmodules.vtkCommonCore import vtkPoints
        rows = vtk_to_numpy(self.polydata.GetPoints().GetData())[np.maximum(
            self.inverse() if inverse is None else inverse, 0)]
        rows[self.copy_rows] = self.copy_points
        rows[self.left_out_rows()] = np.nan
        points = vtkPoints()
        points.SetData(numpy_to_vtk(rows, deep=True))
        return points

    def scatter(self, result, release=()):
        """The input polydata with every point array of `result` (on the merged points) that the input lacks,
        and `result`'s field data, copied to every copy of each position (NaN at a non-finite row, 0 in an integer
        array); the arrays named in `release` (those no one else shares) are emptied once copied (the main job: 10^8
        points' arrays are not held twice)."""
        from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
        from vtkmodules.vtkCommonDataModel import vtkPolyData
        out = vtkPolyData()
        out.ShallowCopy(self.source)
        inverse = self.inverse()  # formed once, for the positions and every array
        out.SetPoints(self.source_points(inverse))
        left_out = self.left_out_rows()
        inverse[left_out] = 0
        arrays = result.GetPointData()
        for i in range(arrays.GetNumberOfArrays()):
            array = arrays.GetArray(i)
            if array is None or out.GetPointData().HasArray(array.GetName()):
                continue
            values = vtk_to_numpy(array)[inverse]
            values[left_out] = np.nan if np.issubdtype(values.dtype, np.floating) else 0
            if array.GetName() in release:  # its distinct values go once copied: one array at a time held twice
                array.Initialize()
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
        if self.non_finite > 0:  # as the filters count them (GLSNonFinitePoints)
            from vtkmodules.vtkCommonCore import vtkIdTypeArray
            count = vtkIdTypeArray()
            count.SetName('GLSNonFinitePoints')
            count.InsertNextValue(self.non_finite)
            out.GetFieldData().AddArray(count)
        return out


def _mixed(z):
    """A 64-bit finalizer (splitmix64's): every input bit moves every output bit, so that coordinates with many
    zero low bits (float32 data in doubles) still give well-spread keys."""
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return z ^ (z >> np.uint64(31))


def distinct_positions(points):
    """(first, inverse): the index of the first copy of each distinct row of `points`, in order of appearance,
    and for every row the index of its distinct position. Rows are equal as floats are (-0.0 is 0.0; a row with a
    NaN equals no other). The rows are sorted by a 64-bit hash of their bits (one stable argsort, about six times
    faster than np.unique(axis=0) at 10M rows), so that equal rows lie next to each other; only the rows whose hash
    another row shares are then compared, by their coordinates (so two different rows that share a hash stay apart).
    About 40 bytes a row at most beside `points` (the rows are hashed a chunk at a time, never copied whole)."""
    first, inverse, _ = _distinct_hashed(points, row_keys(points))
    return first, inverse


def _rows(points):
    """`points` (n x 3, or 3n) as float64 rows with -0.0 made 0.0 (-0.0 + 0.0 is +0.0)."""
    return np.ascontiguousarray(points, dtype=np.float64).reshape(-1, 3) + 0.0


def row_keys(points, chunk=1 << 20):
    """A 64-bit hash of the bits of each row of `points` as _rows gives it (equal rows have equal keys), computed
    `chunk` rows at a time."""
    flat = np.asarray(points).reshape(-1, 3)
    key = np.empty(len(flat), dtype=np.uint64)
    for start in range(0, len(flat), chunk):
        bits = _rows(flat[start:start + chunk]).view(np.uint64)
        with np.errstate(over='ignore'):
            key[start:start + chunk] = _mixed(_mixed(_mixed(bits[:, 0]) ^ bits[:, 1]) ^ bits[:, 2])
    return key


def _distinct_hashed(points, key):
    """distinct_positions of the rows of `points` hashed by row_keys, and the rows that are later copies (each
    row that is not its position's first copy, once), increasing."""
    count = len(key)
    if count == 0:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int32), np.zeros(0, dtype=np.int64)
    # The rows whose key another row shares (a few, in a scan): only they can coincide.
    order = np.argsort(key, kind='stable')
    sorted_key = key[order]
    shared = sorted_key[1:] == sorted_key[:-1]
    del sorted_key
    in_run = np.zeros(count, dtype=bool)
    in_run[1:] |= shared
    in_run[:-1] |= shared
    del shared
    candidates = np.sort(order[in_run])
    del order, in_run
    # Among them, equal bits (NaN rows apart), each group led by its first row.
    later = np.zeros(count, dtype=bool)
    leader_of_later = np.zeros(0, dtype=np.int64)
    later_rows = np.zeros(0, dtype=np.int64)
    if len(candidates) > 1:
        rows = _rows(np.asarray(points).reshape(-1, 3)[candidates])
        bits = rows.view(np.uint64)
        by_bits = np.lexsort((candidates, bits[:, 2], bits[:, 1], bits[:, 0]))
        sorted_bits = bits[by_bits]
        has_nan = np.isnan(rows).any(axis=1)[by_bits]
        starts = np.ones(len(candidates), dtype=bool)
        starts[1:] = ~((sorted_bits[1:] == sorted_bits[:-1]).all(axis=1) & ~has_nan[1:] & ~has_nan[:-1])
        members = candidates[by_bits]
        leaders = members[starts][np.cumsum(starts) - 1]  # each sorted row's group's first row
        copies = ~starts
        later_rows, leader_of_later = members[copies], leaders[copies]
        by_row = np.argsort(later_rows)
        later_rows, leader_of_later = later_rows[by_row], leader_of_later[by_row]
        later[later_rows] = True
    first = np.flatnonzero(~later)
    # A first copy's index among the first copies (32 bits where they fit: 0.4 GB less kept at 10^8 points).
    inverse = np.cumsum(~later, dtype=np.int32 if count < 2 ** 31 else np.int64) - 1
    inverse[later_rows] = inverse[leader_of_later]
    return first, inverse, later_rows


def merged_normals(normals, inverse, count):
    """The normalized mean of the unit normals of each position's copies (NaN where they cancel); rows whose
    position is -1 (left out) count for none."""
    lengths = np.linalg.norm(normals, axis=1)
    with np.errstate(invalid='ignore', divide='ignore'):
        unit = np.where(lengths[:, None] > 0, normals / lengths[:, None], np.nan)
    sums = np.zeros((count, 3))
    analysed = inverse >= 0
    np.add.at(sums, inverse[analysed], unit[analysed])
    norms = np.linalg.norm(sums, axis=1)
    with np.errstate(invalid='ignore', divide='ignore'):
        return np.where(norms[:, None] > 1e-9, sums / norms[:, None], np.nan)


def renumbered_cells(cells, inverse):
    """A copy of a vtkCellArray with every point id replaced by its distinct position's; a cell with a point whose
    position is -1 (left out) is left out."""
    from vtkmodules.util.numpy_support import numpy_to_vtkIdTypeArray, vtk_to_numpy
    from vtkmodules.vtkCommonDataModel import vtkCellArray
    out = vtkCellArray()
    if cells.GetNumberOfCells() == 0:
        return out
    offsets = vtk_to_numpy(cells.GetOffsetsArray()).astype(np.int64)
    connectivity = inverse[vtk_to_numpy(cells.GetConnectivityArray()).astype(np.int64)].astype(np.int64)
    left_out = connectivity < 0
    if left_out.any():
        before = np.concatenate([[0], np.cumsum(left_out)])
        kept = before[offsets[1:]] == before[offsets[:-1]]
        sizes = np.diff(offsets)[kept]
        connectivity = connectivity[np.repeat(kept, np.diff(offsets))]
        offsets = np.concatenate([[0], np.cumsum(sizes)])
    out.SetData(numpy_to_vtkIdTypeArray(np.ascontiguousarray(offsets), deep=True),
                numpy_to_vtkIdTypeArray(np.ascontiguousarray(connectivity), deep=True))
    return out


def finite_rows(points, chunk=1 << 22):
    """Whether each row of `points` (n x 3) has three finite coordinates, `chunk` rows at a time."""
    finite = np.empty(len(points), dtype=bool)
    for start in range(0, len(points), chunk):
        finite[start:start + chunk] = np.isfinite(points[start:start + chunk]).all(axis=1)
    return finite


def merge(polydata):
    """A Merged view of `polydata`, or None when no two of its points coincide and all are finite."""
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    points = vtk_to_numpy(polydata.GetPoints().GetData())
    finite = finite_rows(points)
    all_finite = bool(finite.all())
    key = row_keys(points)
    sorted_key = np.sort(key)
    if all_finite and not np.any(sorted_key[1:] == sorted_key[:-1]):  # no two rows share a hash, so no two
        return None                                     # coincide (a scan's usual case: one unstable sort, a third
    del sorted_key                                      # of the full cost)
    first, inverse, copy_rows = _distinct_hashed(points, key)
    del key
    if len(first) == len(points) and all_finite:
        return None
    if not all_finite:
        # The non-finite rows (NaN ones are each their own position, infinite ones may coincide) join the rows that
        # are not analysed, their position -1; the finite first copies are renumbered among themselves.
        kept = finite[first]
        renumber = np.cumsum(kept, dtype=inverse.dtype) - 1
        renumber[~kept] = -1
        inverse = renumber[inverse]
        first = first[kept]
        copy_rows = np.union1d(copy_rows, np.flatnonzero(~finite))
    del finite
    copy_points = points[copy_rows].copy()
    merged = vtkPolyData()
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(points[first]), deep=True))  # in the input's type
    merged.SetPoints(pts)
    merged.SetVerts(renumbered_cells(polydata.GetVerts(), inverse))
    merged.SetLines(renumbered_cells(polydata.GetLines(), inverse))
    merged.SetPolys(renumbered_cells(polydata.GetPolys(), inverse))
    merged.SetStrips(renumbered_cells(polydata.GetStrips(), inverse))
    for name in CARRIED_ARRAYS:
        array = polydata.GetPointData().GetArray(name)
        if array is not None:
            carried = numpy_to_vtk(np.ascontiguousarray(vtk_to_numpy(array)[first]), deep=True,
                                   array_type=array.GetDataType())
            carried.SetName(name)
            merged.GetPointData().AddArray(carried)
    merged.GetFieldData().ShallowCopy(polydata.GetFieldData())  # the file's sensor, its coordinate system
    normals = polydata.GetPointData().GetArray('Normals')
    if normals is not None and normals.GetNumberOfComponents() == 3:
        averaged = numpy_to_vtk(merged_normals(vtk_to_numpy(normals).astype(float), inverse, len(first)), deep=True)
        averaged.SetName('Normals')
        merged.GetPointData().SetNormals(averaged)
    del points
    copy_targets = inverse[copy_rows].astype(np.int64)
    del inverse
    return Merged(polydata, merged, copy_rows, copy_targets, copy_points)
