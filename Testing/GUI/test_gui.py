"""GUI smoke test (pvpython): starts the real `paraview` client under Xvfb with gui_session.py, then checks that
the screenshots (features, denoised scan, principal directions with glyphs, scale-space image) are not blank, that
the scale-space image, the glyphs and the profiles chart got their data, and that every GLS filter is in the
pipeline.

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


def check_screenshot(name, min_colours):
    shot = os.path.join(work, name)
    if not os.path.isfile(shot):
        failures.append('no screenshot %s' % name)
        return
    reader = vtkPNGReader()
    reader.SetFileName(shot)
    reader.Update()
    image = reader.GetOutput()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(-1, image.GetNumberOfScalarComponents())
    background = np.all(pixels[:, :3] == pixels[0, :3], axis=1).mean()
    colours = len(np.unique(pixels[:, :3], axis=0))
    print('%s %s: %.1f%% background, %d colours' % (name, image.GetDimensions()[:2], 100 * background, colours))
    if background > 0.97 or colours < min_colours:
        failures.append('blank screenshot %s (%.1f%% background, %d colours)' % (name, 100 * background, colours))


# The features, the denoised scan and the scale-space image (Slice representation).
for name in ('gui.png', 'denoised.png', 'directions.png', 'image.png'):
    check_screenshot(name, 200)
# The glyphs of the chosen scale's directions: a line (two points or more) for every 5th of the 35,947 points.
glyph_file = os.path.join(work, 'glyph-points.txt')
glyph_points = int(open(glyph_file).read()) if os.path.isfile(glyph_file) else 0
if glyph_points < 2 * (35947 // 5):
    failures.append('the principal directions show %d glyph points, fewer than a line per 5th point' % glyph_points)
points_file = os.path.join(work, 'image-points.txt')
shown = int(open(points_file).read()) if os.path.isfile(points_file) else 0
if shown != 1000 * 200:
    failures.append('the scale-space image shows %d points, not 1000 x 200' % shown)

# The scale profiles in a line chart view: 200 rows (the proxy's default scales), the points' series listed.
chart_file = os.path.join(work, 'chart.txt')
chart = open(chart_file).read().split('\n') if os.path.isfile(chart_file) else ['0']
if int(chart[0]) != 200 or 't*kappa (100)' not in chart or 'nu (2000)' not in chart:
    failures.append('the profiles chart has %s rows and series %s' % (chart[0], chart[1:]))

pipeline = os.path.join(work, 'pipeline.txt')
names = open(pipeline).read().split('\n') if os.path.isfile(pipeline) else []
for expected in ('GLS Normal Estimation', 'GLS Scale Space', 'GLS Geometric Variation', 'GLS Continuous Features',
                 'GLS Dissimilarity', 'GLS Adaptive Bandwidth', 'GLS Projection', 'GLS Scale Profiles',
                 'GLS Scale Space Image', 'GLS Principal Directions', 'Glyph'):
    if expected not in names:
        failures.append('%r missing from the pipeline %s' % (expected, names))

for f in failures:
    print('FAIL: ' + f)
print('%d failures' % len(failures))
sys.exit(1 if failures else 0)
