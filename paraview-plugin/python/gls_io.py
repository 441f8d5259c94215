"""Point-cloud input for the GLS main job: PLY, OBJ, VTP through ParaView's readers, XYZ/CSV through a small
parser of our own (x y z [nx ny nz], separated by spaces, tabs, commas or semicolons; '#' comments and one
header line are allowed)."""
import os
import re

import numpy as np

SUPPORTED = ('.ply', '.obj', '.vtp', '.xyz', '.csv', '.txt', '.pts')


class InputError(Exception):
    """A missing, unreadable or malformed input file, with a message for the user."""


def parse_xyz(path):
    """Returns (points (N, 3), normals (N, 3) or None) from a text point file; raises InputError."""
    rows = []
    width = None
    with open(path, 'r', encoding='utf-8', errors='replace') as f:
        for number, line in enumerate(f, 1):
            text = line.split('#', 1)[0].strip()
            if not text:
                continue
            fields = [v for v in re.split(r'[\s,;]+', text) if v]
            try:
                values = [float(v) for v in fields]
            except ValueError:
                if not rows and number <= 2:
                    continue  # a header line such as "x,y,z,nx,ny,nz"
                raise InputError('%s:%d: not a number in %r' % (path, number, text[:60]))
            if width is None:
                width = len(values)
                if width not in (3, 6) and width < 3:
                    raise InputError('%s:%d: expected 3 (x y z) or 6 (x y z nx ny nz) columns, got %d'
                                     % (path, number, width))
            if len(values) != width:
                raise InputError('%s:%d: expected %d columns like the first row, got %d'
                                 % (path, number, width, len(values)))
            rows.append(values)
    if not rows:
        raise InputError('%s: no points found' % path)
    data = np.asarray(rows, dtype=np.float64)
    normals = data[:, 3:6] if width >= 6 else None
    return data[:, 0:3], normals


def to_polydata(points, normals):
    """A vertex vtkPolyData with the given points and optional normals ('Normals', active)."""
    from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
    pd = vtkPolyData()
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(points), deep=True))
    pd.SetPoints(pts)
    n = len(points)
    cells = vtkCellArray()
    cells.SetData(numpy_to_vtkIdTypeArray(np.arange(n + 1, dtype=np.int64), deep=True),
                  numpy_to_vtkIdTypeArray(np.arange(n, dtype=np.int64), deep=True))
    pd.SetVerts(cells)
    if normals is not None:
        arr = numpy_to_vtk(np.ascontiguousarray(normals), deep=True)
        arr.SetName('Normals')
        pd.GetPointData().SetNormals(arr)
    return pd


def open_cloud(path):
    """A ParaView source proxy producing the file's points (and normals if any); raises InputError."""
    from paraview import simple
    if not os.path.isfile(path):
        raise InputError('%s: no such file' % path)
    if not os.access(path, os.R_OK):
        raise InputError('%s: not readable (permissions)' % path)
    ext = os.path.splitext(path)[1].lower()
    if ext not in SUPPORTED:
        raise InputError('%s: unsupported type %r (use %s)' % (path, ext, ', '.join(SUPPORTED)))
    if ext in ('.xyz', '.csv', '.txt', '.pts'):
        points, normals = parse_xyz(path)
        source = simple.TrivialProducer(registrationName=os.path.basename(path))
        source.GetClientSideObject().SetOutput(to_polydata(points, normals))
        source.UpdatePipeline()
        return source
    reader = simple.OpenDataFile(path)
    if reader is None:
        raise InputError('%s: ParaView has no reader for it' % path)
    reader.UpdatePipeline()
    info = reader.GetDataInformation()
    if info.GetNumberOfPoints() == 0:
        raise InputError('%s: unreadable or empty (no points)' % path)
    return reader
