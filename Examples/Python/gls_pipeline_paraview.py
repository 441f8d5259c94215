"""The GLS pipeline in pvpython with paraview.simple and the installed ParaView plugin: oriented normals unless the
file has them, the scale space (20 quadratic scales from 0.8% to 8% of the bounding-box diagonal), the geometric
variation, the continuous features and the multi-scale dissimilarity to one query point; every array goes to a .vtp.

    PV_PLUGIN_PATH=<prefix>/lib/paraview-5.11/plugins pvpython gls_pipeline_paraview.py <input> [output.vtp] [query id]

<input>: .obj .ply .vtp (ParaView's readers) or .xyz .pts .csv .txt (the plugin's GLS Point Cloud Reader).
Exit status: 0 on success, 1 when the input cannot be read or a filter fails, 2 on bad arguments.
"""
import os
import sys

import gls_example_io  # this directory: the command line and the output, shared with gls_pipeline_vtk.py
from paraview import servermanager, simple

path, output, query = gls_example_io.arguments(__doc__.split('\n\n')[1])

# Finds GrowingLeastSquares.so in the directories of PV_PLUGIN_PATH; adds the GLS proxies to this module's namespace
# (ns=globals(): a fresh dict passed as ns stays empty in ParaView 5.11).
simple.LoadDistributedPlugin('GrowingLeastSquares', remote=False, ns=globals())

if os.path.splitext(path)[1].lower() in ('.xyz', '.pts', '.csv', '.txt'):
    cloud = GLSPointCloudReader(FileName=path)  # noqa: F821 (defined by LoadDistributedPlugin)
else:
    cloud = simple.OpenDataFile(path)
if cloud is not None:
    cloud.UpdatePipeline()
if cloud is None or cloud.GetDataInformation().GetNumberOfPoints() == 0:
    sys.exit('error: %s: no points read' % path)

if cloud.PointData.GetArray('Normals') is None:
    cloud = GLSNormalEstimation(Input=cloud)  # noqa: F821 (16 nearest, minimum-spanning-tree orientation)
scale_space = GLSScaleSpace(Input=cloud)  # noqa: F821 (defaults: 20 quadratic scales, 0.8% to 8% of the diagonal)
variation = GLSGeometricVariation(Input=scale_space)  # noqa: F821 (nu per scale, from the stored scale space)
features = GLSContinuousFeatures(Input=variation)  # noqa: F821 (f in [0, 1])
dissimilarity = GLSMultiScaleDissimilarity(Input=features, QueryPointId=query)  # noqa: F821

result = servermanager.Fetch(dissimilarity)  # a vtkPolyData with every GLS array
gls_example_io.report_and_write(result, output, query)
