"""Runs inside the real ParaView GUI (paraview --script=gui_session.py --exit, under Xvfb): loads the plugin,
applies the GLS filters to the bundled scan as a user would, renders, saves a screenshot and the pipeline's
source names to GLS_GUI_OUT."""
import math
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

# The applications and views, shown one after the other in the same render view: the denoised scan, the
# scale-space image of a curve (Slice representation); then the scale profiles in a line chart view.
bandwidth = GLSAdaptiveBandwidth(registrationName='GLS Adaptive Bandwidth', Input=normals,  # noqa: F405
                                 MinScale=0.004, MaxScale=0.02, NumberOfScales=20, ScaleSampling='Logarithmic')
denoised = GLSProjection(registrationName='GLS Projection', Input=bandwidth)  # noqa: F405
Hide(features, view)
denoised_display = Show(denoised, view)
ColorBy(denoised_display, ('POINTS', 'GLSDisplacement'))
view.ResetCamera()
Render(view)
SaveScreenshot(os.path.join(out, 'denoised.png'), view, ImageResolution=[800, 600])

# The principal directions of one chosen scale as glyphs (lines along d1, the filter's active vectors) over the scan.
directions = GLSPrincipalDirections(registrationName='GLS Principal Directions', Input=normals,  # noqa: F405
                                    NumberOfScales=8, DirectionScale=0.02)
glyphs = Glyph(registrationName='Glyph', Input=directions, GlyphType='Line',  # noqa: F405
               OrientationArray=['POINTS', 'GLSPrincipalDirection1AtScale'], ScaleArray=['POINTS', 'No scale array'],
               ScaleFactor=0.004, GlyphMode='Every Nth Point', Stride=5)
Hide(denoised, view)
directions_display = Show(directions, view)
ColorBy(directions_display, ('POINTS', 'GLSStableShapeIndex'))
glyphs_display = Show(glyphs, view)
ColorBy(glyphs_display, None)
view.ResetCamera()
Render(view)
SaveScreenshot(os.path.join(out, 'directions.png'), view, ImageResolution=[800, 600])
with open(os.path.join(out, 'glyph-points.txt'), 'w') as f:
    f.write('%d\n' % glyphs.GetDataInformation().GetNumberOfPoints())
Hide(directions, view)
Hide(glyphs, view)

theta = [2 * math.pi * i / 300 for i in range(300)]
flower = PolyLineSource(registrationName='Flower curve', Closed=1,  # noqa: F405
                        Points=[c for t in theta for c in ((1 + 0.25 * math.cos(5 * t)) * math.cos(t),
                                                            (1 + 0.25 * math.cos(5 * t)) * math.sin(t), 0.0)])
image = GLSScaleSpaceImage(registrationName='GLS Scale Space Image', Input=flower,  # noqa: F405
                           ScaleUnits='Absolute', MinScale=0.05, MaxScale=3.0)
image_display = Show(image, view)
image_display.SetRepresentationType('Slice')
ColorBy(image_display, ('POINTS', 'GLSScaledKappa'))
view.ResetCamera()
Render(view)
SaveScreenshot(os.path.join(out, 'image.png'), view, ImageResolution=[800, 600])
with open(os.path.join(out, 'image-points.txt'), 'w') as f:
    f.write('%d\n' % image_display.GetRepresentedDataInformation().GetNumberOfPoints())

profiles = GLSScaleProfiles(registrationName='GLS Scale Profiles', Input=normals, PointIds=[100, 2000])  # noqa: F405
# (A chart view outside the GUI's layout cannot be captured, and splitting the layout from a --script run hangs
# ParaView 5.11: the chart's series and the table's rows are recorded instead.)
chart = CreateView('XYChartView')
chart_display = Show(profiles, chart)
chart_display.UseIndexForXAxis = 0
chart_display.XArrayName = 't'
chart_display.SeriesVisibility = ['t*kappa (100)', 't*kappa (2000)']
Render(chart)
with open(os.path.join(out, 'chart.txt'), 'w') as f:
    f.write('%d\n%s\n' % (profiles.GetDataInformation().GetNumberOfRows(),
                           '\n'.join(str(name) for name in chart_display.SeriesLabel)))

with open(os.path.join(out, 'pipeline.txt'), 'w') as f:
    f.write('\n'.join(sorted(name for name, _ in GetSources().keys())) + '\n')
