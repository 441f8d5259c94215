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

import gls_example_io  # this directory: the command line and the output, shared with gls_pipeline_paraview.py

try:
    from vtkmodules.vtkIOGeometry import vtkOBJReader
    from vtkmodules.vtkIOPLY import vtkPLYReader
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    from glsvtk import (vtkGLSContinuousFeatures, vtkGLSGeometricVariation, vtkGLSMultiScaleDissimilarity,
                        vtkGLSNormalEstimation, vtkGLSPointCloudReader, vtkGLSScaleSpace)
except ImportError as error:
    sys.exit('error: %s (%s). Run Debian\'s /usr/bin/python3 with PYTHONPATH=<prefix>/lib/python3/dist-packages.'
             % (error, sys.executable))

READERS = {'.obj': vtkOBJReader, '.ply': vtkPLYReader, '.vtp': vtkXMLPolyDataReader, '.xyz': vtkGLSPointCloudReader,
           '.pts': vtkGLSPointCloudReader, '.csv': vtkGLSPointCloudReader, '.txt': vtkGLSPointCloudReader}

path, output, query = gls_example_io.arguments(__doc__.split('\n\n')[1])

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
gls_example_io.report_and_write(result, output, query)
