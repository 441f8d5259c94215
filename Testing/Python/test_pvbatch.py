"""pvbatch runs the plugin's filters like pvpython: features on a tessellated sphere are ~0 and equal to the wrapped
C++ filter's.

    pvbatch test_pvbatch.py <plugin.so>   (PYTHONPATH holding glsvtk)"""
import sys

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from vtkmodules.util.numpy_support import vtk_to_numpy

import glsvtk

LoadPlugin(sys.argv[1], remote=False, ns=globals())
sphere = Sphere(ThetaResolution=60, PhiResolution=60, Radius=1.5)  # noqa: F405
features = GLSContinuousFeatures(Input=sphere, NumberOfScales=4, MinScale=0.05, MaxScale=0.2)  # noqa: F405
features.UpdatePipeline()
proxy_f = vtk_to_numpy(servermanager.Fetch(features).GetPointData().GetArray('GLSFeature'))

direct = glsvtk.vtkGLSContinuousFeatures()
direct.SetNumberOfScales(4)
direct.SetMinScale(0.05)
direct.SetMaxScale(0.2)
direct.SetInputData(servermanager.Fetch(sphere))
direct.Update()
direct_f = vtk_to_numpy(direct.GetOutput().GetPointData().GetArray('GLSFeature'))

failures = 0
if not np.array_equal(proxy_f, direct_f, equal_nan=True):
    print('FAIL: proxy and wrapped filter differ')
    failures += 1
if not (np.nanmax(proxy_f) < 0.05 and np.nanmedian(proxy_f) < 0.01):
    print('FAIL: a sphere should have no features: max %g median %g' % (np.nanmax(proxy_f), np.nanmedian(proxy_f)))
    failures += 1
print('%d passed, %d failed' % (2 - failures, failures))
sys.exit(1 if failures else 0)
