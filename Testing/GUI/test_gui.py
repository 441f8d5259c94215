"""GUI smoke test (pvpython): starts the real `paraview` client under Xvfb with gui_session.py, then checks that
the screenshot is not blank and that every GLS filter is in the pipeline.

    pvpython test_gui.py <plugin.so> <bunny.obj> <work dir>"""
import os
import shutil
import subprocess
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

plugin, bunny, work = sys.argv[1:4]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
env = dict(os.environ, GLS_PLUGIN=plugin, GLS_DEFAULT_INPUT=bunny, GLS_GUI_OUT=work)
env.pop('DISPLAY', None)  # always a private virtual X server
session = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'gui_session.py')
display = os.path.join(os.path.dirname(session), '..', '..', 'paraview-plugin', 'python', 'with-virtual-display')
command = [display, 'paraview', '--script=' + session, '--exit']
result = subprocess.run(command, env=env, capture_output=True, text=True, timeout=240)
print(result.stdout[-2000:], result.stderr[-2000:])
failures = []
if result.returncode != 0:
    failures.append('paraview exited with %d' % result.returncode)

shot = os.path.join(work, 'gui.png')
if not os.path.isfile(shot):
    failures.append('no screenshot')
else:
    reader = vtkPNGReader()
    reader.SetFileName(shot)
    reader.Update()
    image = reader.GetOutput()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(-1, image.GetNumberOfScalarComponents())
    background = np.all(pixels[:, :3] == pixels[0, :3], axis=1).mean()
    colours = len(np.unique(pixels[:, :3], axis=0))
    print('screenshot %s: %.1f%% background, %d colours' % (image.GetDimensions()[:2], 100 * background, colours))
    if background > 0.97 or colours < 200:
        failures.append('blank screenshot (%.1f%% background, %d colours)' % (100 * background, colours))

pipeline = os.path.join(work, 'pipeline.txt')
names = open(pipeline).read().split('\n') if os.path.isfile(pipeline) else []
for expected in ('GLS Normal Estimation', 'GLS Scale Space', 'GLS Geometric Variation', 'GLS Continuous Features',
                 'GLS Dissimilarity'):
    if expected not in names:
        failures.append('%r missing from the pipeline %s' % (expected, names))

for f in failures:
    print('FAIL: ' + f)
print('%d passed, %d failed' % (0 if failures else 1, 1 if failures else 0))
sys.exit(1 if failures else 0)
