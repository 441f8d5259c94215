"""The GLS pipeline in plain VTK Python: the installed glsvtk package on ParaView's VTK (vtkmodules), no ParaView
server. Oriented normals unless the file has them, the scale space (20 quadratic scales from 0.8% to 8% of the
bounding-box diagonal), the geometric variation, the continuous features and the multi-scale dissimilarity to one
query point; every array goes to a .vtp.

    PYTHONPATH=<prefix>/lib/python3/dist-packages /usr/bin/python3 gls_pipeline_vtk.py <input> [output.vtp] [query id]

Run it with Debian's /usr/bin/python3 (the interpreter ParaView's vtkmodules and glsvtk are built for; pvpython works
too). <input>: .obj .ply .vtp .xyz .pts .csv .txt. Exit status: 0 on success, 1 when the input cannot be read or a
filter fails, 2 on bad arguments.
"""
import os
import sys

try:
    from vtkmodules.vtkIOGeometry import vtkOBJReader
    from vtkmodules.vtkIOPLY import vtkPLYReader
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter
    from glsvtk import (vtkGLSContinuousFeatures, vtkGLSGeometricVariation, vtkGLSMultiScaleDissimilarity,
                        vtkGLSNormalEstimation, vtkGLSPointCloudReader, vtkGLSScaleSpace)
except ImportError as error:
    sys.exit('error: %s (%s). Run Debian\'s /usr/bin/python3 with PYTHONPATH=<prefix>/lib/python3/dist-packages.'
             % (error, sys.executable))

READERS = {'.obj': vtkOBJReader, '.ply': vtkPLYReader, '.vtp': vtkXMLPolyDataReader, '.xyz': vtkGLSPointCloudReader,
           '.pts': vtkGLSPointCloudReader, '.csv': vtkGLSPointCloudReader, '.txt': vtkGLSPointCloudReader}

if not 2 <= len(sys.argv) <= 4:
    print(__doc__.split('\n\n')[1], file=sys.stderr)
    sys.exit(2)
path = sys.argv[1]
output = sys.argv[2] if len(sys.argv) > 2 else 'gls-example.vtp'
query = int(sys.argv[3]) if len(sys.argv) > 3 else 0

reader_class = READERS.get(os.path.splitext(path)[1].lower())
if reader_class is None:
    print('error: %s: unsupported file type' % path, file=sys.stderr)
    sys.exit(2)
reader = reader_class()
reader.SetFileName(path)
reader.Update()
if reader.GetOutput().GetNumberOfPoints() == 0:
    sys.exit('error: %s: no points read' % path)

last = reader
if reader.GetOutput().GetPointData().GetNormals() is None:
    last = vtkGLSNormalEstimation()  # 16 nearest, minimum-spanning-tree orientation
    last.SetInputConnection(reader.GetOutputPort())
scale_space = vtkGLSScaleSpace()  # defaults: 20 quadratic scales, 0.8% to 8% of the diagonal
scale_space.SetInputConnection(last.GetOutputPort())
variation = vtkGLSGeometricVariation()  # nu per scale, from the stored scale space
variation.SetInputConnection(scale_space.GetOutputPort())
features = vtkGLSContinuousFeatures()  # f in [0, 1]
features.SetInputConnection(variation.GetOutputPort())
dissimilarity = vtkGLSMultiScaleDissimilarity()
dissimilarity.SetInputConnection(features.GetOutputPort())
dissimilarity.SetQueryPointId(query)
dissimilarity.Update()

result = dissimilarity.GetOutput()
f = result.GetPointData().GetArray('GLSFeature')
delta = result.GetPointData().GetArray('GLSDissimilarity')
if f is None or delta is None:
    sys.exit('error: the pipeline failed (see the messages above)')
print('%d points; GLSFeature in [%g, %g]; GLSDissimilarity to point %d in [%g, %g]'
      % ((result.GetNumberOfPoints(),) + f.GetRange() + (query,) + delta.GetRange()))

writer = vtkXMLPolyDataWriter()
writer.SetFileName(output)
writer.SetInputData(result)
writer.SetDataModeToBinary()  # inline binary: ParaView 5.11 misreads some appended files with many components
if writer.Write() != 1:
    sys.exit('error: cannot write %s' % output)
print('wrote %s' % output)
