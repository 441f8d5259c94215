"""Runs inside the real ParaView GUI (paraview --script=gui_session.py --exit, under Xvfb): loads the plugin,
applies the GLS filters to the bundled scan as a user would, renders, saves a screenshot and the pipeline's
source names to GLS_GUI_OUT."""
import os

from paraview.simple import *  # noqa: F401,F403 (the GUI's Python shell idiom)

out = os.environ['GLS_GUI_OUT']
LoadPlugin(os.environ['GLS_PLUGIN'], remote=False, ns=globals())
reader = OpenDataFile(os.environ['GLS_DEFAULT_INPUT'])
normals = GLSNormalEstimation(registrationName='GLS Normal Estimation', Input=reader)  # noqa: F405
scales = GLSScaleSpace(registrationName='GLS Scale Space', Input=normals, NumberOfScales=12)  # noqa: F405
variation = GLSGeometricVariation(registrationName='GLS Geometric Variation', Input=scales)  # noqa: F405
features = GLSContinuousFeatures(registrationName='GLS Continuous Features', Input=variation)  # noqa: F405
similar = GLSMultiScaleDissimilarity(registrationName='GLS Dissimilarity', Input=features,  # noqa: F405
                                     QueryPointId=100)
view = GetActiveViewOrCreate('RenderView')
display = Show(features, view)
ColorBy(display, ('POINTS', 'GLSFeature'))
display.SetScalarBarVisibility(view, True)
view.ResetCamera()
Render(view)
SaveScreenshot(os.path.join(out, 'gui.png'), view, ImageResolution=[800, 600])
with open(os.path.join(out, 'pipeline.txt'), 'w') as f:
    f.write('\n'.join(sorted(name for name, _ in GetSources().keys())) + '\n')
