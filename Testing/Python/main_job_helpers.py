"""Shared by the main-job tests: running gls-analyze as a user does (no display), reading what it wrote, and
writing input files (shapes.sphere: points exactly on a sphere, with exact normals). Importing it also makes the
main job's own modules (paraview-plugin/python) importable, for the tests of its parts."""
import os
import re
import subprocess
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

from shapes import sphere

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'paraview-plugin', 'python'))


def run(analyze, *args, **popen):
    """Runs the main job as a user does, without a display (its own virtual X server, as on a headless machine);
    `popen`: more of subprocess.run's arguments (a preexec_fn)."""
    env = dict(os.environ)
    env.pop('DISPLAY', None)
    return subprocess.run([analyze, *args], capture_output=True, text=True, timeout=300, env=env, **popen)


def failure_text(result):
    """The error lines of a failed run first (a crash's stack trace would push them out of a plain tail)."""
    errors = [line for line in result.stderr.splitlines()
              if ('ERR|' in line or 'Error' in line or 'error' in line) and 'L2_NORM' not in line]
    return '\n'.join(errors[:20]) + '\n...\n' + result.stderr[-1500:]


def error_lines(result):
    """The main job's own error lines (its warnings and the progress lines left out)."""
    return [line for line in result.stderr.splitlines()
            if line.startswith('gls-analyze: ') and not line.startswith('gls-analyze: warning: ')]


def denoising_rms(stdout):
    """The main job's "RMS distance to the input surface A -> B" figures."""
    m = re.search(r'RMS distance to the input surface (\S+) -> (\S+)', stdout)
    return float(m.group(1)), float(m.group(2))


def read_vtp(path):
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def point_array(polydata, name):
    array = polydata.GetPointData().GetArray(name)
    return None if array is None else vtk_to_numpy(array)


def read_png(path):
    """The picture's pixels as rows x columns x RGB (row 0 at the bottom, as VTK stores them)."""
    from vtkmodules.vtkIOImage import vtkPNGReader
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, -1)
    return pixels[:, :, :3]


def image_stats(path):
    """(fraction of pixels of the background colour, number of distinct colours)."""
    rgb = read_png(path).reshape(-1, 3)
    background = np.all(rgb == rgb[0], axis=1).mean()
    return background, len(np.unique(rgb, axis=0))


def central_background(path):
    """The fraction of the middle of the picture (half its height, a third of its width) in the background colour
    (that of its corner pixel): 1 for a picture that shows nothing there."""
    rgb = read_png(path)
    h, w, _ = rgb.shape
    return float(np.all(rgb[h // 4:3 * h // 4, w // 3:2 * w // 3] == rgb[0, 0], axis=2).mean())


def write_sphere(path, n, radius, with_normals, separator, header=None):
    points, normals = sphere(n, radius)
    data = np.hstack([points, normals]) if with_normals else points
    np.savetxt(path, data, delimiter=separator, header=header or '', comments='')


def polydata_from(points, normals=None, vertices=True):
    """A polydata of the points, with one vertex cell each when `vertices`, and float Normals when given."""
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
    pd = vtkPolyData()
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(points), deep=True))
    pd.SetPoints(pts)
    if vertices:
        verts = vtkCellArray()
        for i in range(len(points)):
            verts.InsertNextCell(1)
            verts.InsertCellPoint(i)
        pd.SetVerts(verts)
    if normals is not None:
        n = numpy_to_vtk(np.ascontiguousarray(normals, dtype=np.float32), deep=True)  # PLY keeps float normals
        n.SetName('Normals')
        pd.GetPointData().SetNormals(n)
    return pd


def write_ply(path, polydata, binary=False):
    from vtkmodules.vtkIOPLY import vtkPLYWriter
    writer = vtkPLYWriter()
    writer.SetFileName(path)
    writer.SetInputData(polydata)
    if binary:
        writer.SetFileTypeToBinary()
    else:
        writer.SetFileTypeToASCII()
    writer.Write()


def read_ply(file):
    """The vertices of a binary little-endian PLY file whose first element is the vertex, as a numpy record array,
    read from the format's description (independently of the project's writer)."""
    types = {'char': 'i1', 'uchar': 'u1', 'short': '<i2', 'ushort': '<u2', 'int': '<i4', 'uint': '<u4',
             'float': '<f4', 'double': '<f8'}
    with open(file, 'rb') as f:
        data = f.read()
    end = data.index(b'end_header\n') + len(b'end_header\n')
    fields, count, element = [], 0, None
    for line in data[:end].decode('ascii').splitlines():
        words = line.split()
        if words[:1] == ['format']:
            assert words[1] == 'binary_little_endian', line
        elif words[:1] == ['element']:
            element = words[1]
            if element == 'vertex':
                count = int(words[2])
        elif words[:1] == ['property'] and element == 'vertex':
            fields.append((words[2], types[words[1]]))
    return np.frombuffer(data, dtype=np.dtype(fields), count=count, offset=end)
