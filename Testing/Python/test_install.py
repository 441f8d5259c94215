"""The installed plugin loads the way ParaView finds plugins (pvpython, no build-tree paths).

    pvpython test_install.py <install prefix>   (PV_PLUGIN_PATH=<prefix>/lib/paraview-5.11/plugins)"""
import os
import sys

import numpy as np
from paraview import simple, servermanager
from vtkmodules.util.numpy_support import vtk_to_numpy

prefix = sys.argv[1]
plugin_dir = os.path.join(prefix, 'lib', 'paraview-5.11', 'plugins', 'GrowingLeastSquares')
assert os.path.isfile(os.path.join(plugin_dir, 'GrowingLeastSquares.so')), os.listdir(prefix)
simple.LoadDistributedPlugin('GrowingLeastSquares', remote=False, ns=globals())  # a fresh dict stays empty
sphere = simple.Sphere(ThetaResolution=80, PhiResolution=80, Radius=2.0)
scale_space = globals()['GLSScaleSpace'](Input=sphere, NumberOfScales=3, MinScale=0.1, MaxScale=0.3)
scale_space.UpdatePipeline()
kappa = vtk_to_numpy(servermanager.Fetch(scale_space).GetPointData().GetArray('GLSKappa'))
# A tessellated sphere with its vertex normals: curvature 1/2 up to the tessellation error.
assert abs(np.nanmedian(kappa) - 0.5) < 0.01, np.nanmedian(kappa)
sys.path.insert(0, os.path.join(prefix, 'lib', 'python3', 'dist-packages'))
import glsvtk  # noqa: E402
assert glsvtk.vtkGLSScaleSpace().GetNumberOfScales() == 20
print('1 passed, 0 failed')
