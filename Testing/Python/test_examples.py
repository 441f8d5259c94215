"""The examples against an installed prefix, as a user runs them: Examples/Cxx configured and built with nothing but
CMAKE_PREFIX_PATH (a fresh build directory, a clean environment), the pvpython example with PV_PLUGIN_PATH, the plain
VTK Python example with /usr/bin/python3 and PYTHONPATH; each output checked, the three against each other and the
in-tree build, and the C++ one on a sphere against the exact curvature. Also: the package rejects another VTK with
a message naming VTK_DIR, and the installed gls-analyze runs from the prefix.

    /usr/bin/python3 test_examples.py --prefix P --source S --build B --work W --pvpython PV --data BUNNY.obj
"""
import argparse
import os
import shutil
import subprocess
import sys
import unittest

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkObject
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

# The arrays of each stage of the examples' pipeline (normals, scale space, variation, features, dissimilarity).
STAGE_ARRAYS = ('Normals', 'GLSKappa', 'GLSGeometricVariation', 'GLSFeature', 'GLSDissimilarity', 'GLSSimilar')
QUERY = 17
SPHERE_RADIUS = 2.0


def parse_arguments():
    p = argparse.ArgumentParser()
    for name in ('prefix', 'source', 'build', 'work', 'pvpython', 'data'):
        p.add_argument('--' + name, required=True)
    p.add_argument('--cmake', default='cmake')
    p.add_argument('--python3', default='/usr/bin/python3')
    args, rest = p.parse_known_args()
    return args, rest


ARGS, UNITTEST_ARGV = parse_arguments()


def clean_environment(**extra):
    """The environment of a user who has set nothing GLS-, VTK- or ParaView-specific, plus `extra`."""
    env = {k: v for k, v in os.environ.items()
           if k not in ('PYTHONPATH', 'PV_PLUGIN_PATH', 'VTK_DIR', 'ParaView_DIR', 'CMAKE_PREFIX_PATH', 'DISPLAY')
           and not k.startswith('GLS_')}
    env.update(extra)
    return env


def run(command, env=None, cwd=None):
    result = subprocess.run(command, capture_output=True, text=True, timeout=600, env=env or clean_environment(),
                            cwd=cwd)
    return result


def check(result):
    if result.returncode != 0:
        raise AssertionError('%s failed (%d):\n%s\n%s' % (' '.join(result.args), result.returncode,
                                                           result.stdout[-3000:], result.stderr[-3000:]))
    return result


def read_arrays(path):
    """Every point-data array of a .vtp as numpy (VTK 9.2's reader errors on its own L2_NORM_RANGE keys: muted)."""
    vtkObject.GlobalWarningDisplayOff()
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    pd = reader.GetOutput().GetPointData()
    return {pd.GetArrayName(i): vtk_to_numpy(pd.GetArray(i)).astype(float) for i in range(pd.GetNumberOfArrays())}


def write_sphere(path, n):
    """n points on a sphere of radius SPHERE_RADIUS centred at (1, 2, 3), with their exact outward normals."""
    i = np.arange(n) + 0.5
    z = 1 - 2 * i / n
    r = np.sqrt(1 - z * z)
    a = np.pi * (1 + 5 ** 0.5) * i
    u = np.stack([r * np.cos(a), r * np.sin(a), z], axis=1)
    np.savetxt(path, np.hstack([SPHERE_RADIUS * u + [1.0, 2.0, 3.0], u]), fmt='%.17g')


def assert_arrays_equal(test, expected, actual, what):
    """Same arrays, same NaN pattern, values within 1e-12 of the array's largest magnitude."""
    for name in STAGE_ARRAYS:
        a, b = expected[name], actual[name]
        test.assertEqual(a.shape, b.shape, '%s %s' % (what, name))
        test.assertTrue(np.array_equal(np.isnan(a), np.isnan(b)), '%s %s: NaN pattern' % (what, name))
        finite = np.isfinite(a)
        scale = max(np.max(np.abs(a[finite])), 1e-300)
        test.assertLessEqual(np.max(np.abs(a[finite] - b[finite])), 1e-12 * scale, '%s %s' % (what, name))


class Examples(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.work = os.path.abspath(ARGS.work)
        shutil.rmtree(cls.work, ignore_errors=True)
        os.makedirs(cls.work)
        cls.sphere = os.path.join(cls.work, 'sphere.xyz')
        write_sphere(cls.sphere, 6000)
        cls.outputs = {}

    def output(self, name):
        return os.path.join(self.work, name + '.vtp')

    def cxx_example(self):
        """Examples/Cxx configured and built against the prefix in a fresh directory (once); its executable."""
        exe = os.path.join(self.work, 'cxx-build', 'glsExample')
        if not os.path.isfile(exe):
            build = os.path.dirname(exe)
            check(run([ARGS.cmake, '-S', os.path.join(ARGS.source, 'Examples', 'Cxx'), '-B', build,
                       '-DCMAKE_BUILD_TYPE=Release', '-DCMAKE_PREFIX_PATH=' + os.path.abspath(ARGS.prefix)]))
            check(run([ARGS.cmake, '--build', build, '-j2']))
        return exe

    def test_installed_package_files(self):
        cmake_dir = os.path.join(ARGS.prefix, 'lib', 'cmake', 'GrowingLeastSquares')
        for name in ('GrowingLeastSquaresConfig.cmake', 'GrowingLeastSquaresConfigVersion.cmake',
                     'GrowingLeastSquares-targets.cmake', 'GrowingLeastSquares-vtk-module-properties.cmake'):
            self.assertTrue(os.path.isfile(os.path.join(cmake_dir, name)), name)
        with open(os.path.join(cmake_dir, 'GrowingLeastSquares-targets.cmake')) as f:
            targets = f.read()
        # A shared module holds the core: the core is no user target, and nothing names Eigen.
        self.assertIn('add_library(GLS::Filters SHARED IMPORTED)', targets)
        self.assertNotIn('gls_core', targets)
        self.assertNotIn('Eigen', targets)

    def test_cxx_example_on_the_bunny_equals_the_in_tree_build(self):
        check(run([self.cxx_example(), ARGS.data, self.output('cxx'), str(QUERY)]))
        check(run([os.path.join(ARGS.build, 'bin', 'glsExample'), ARGS.data, self.output('in-tree'), str(QUERY)]))
        ours = read_arrays(self.output('cxx'))
        for name in STAGE_ARRAYS:
            self.assertIn(name, ours)
        n = len(ours['GLSFeature'])
        self.assertEqual(n, 35947)
        normals = ours['Normals']
        np.testing.assert_allclose(np.linalg.norm(normals, axis=1), 1.0, atol=1e-12)
        feature = ours['GLSFeature']
        self.assertTrue(np.all((feature >= 0) & (feature <= 1)), 'features finite, in [0, 1]')
        self.assertGreater(feature.std(), 0.1)  # not a constant
        delta = ours['GLSDissimilarity']
        self.assertTrue(np.all(np.isfinite(delta) & (delta >= 0)))
        self.assertEqual(delta[QUERY], 0.0)
        self.assertTrue(set(np.unique(ours['GLSSimilar'])) <= {0.0, 1.0})
        self.assertEqual(ours['GLSSimilar'][QUERY], 1.0)
        # The coarsest scale: every point has its fit (the bunny is dense); kappa mostly positive (outward normals).
        kappa = ours['GLSKappa'].reshape(n, -1)
        self.assertTrue(np.all(np.isfinite(kappa[:, -1])))
        self.assertGreater(np.mean(kappa[:, -1] > 0), 0.6)
        assert_arrays_equal(self, read_arrays(self.output('in-tree')), ours, 'installed vs in-tree C++ example')

    def test_cxx_example_on_a_sphere_gives_its_curvature(self):
        check(run([self.cxx_example(), self.sphere, self.output('sphere'), '5']))
        sphere = read_arrays(self.output('sphere'))
        kappa = sphere['GLSKappa'].reshape(6000, -1)
        # Fits with fewer than 6 neighbours (the finest scales here) are NaN; every fit made is the sphere itself.
        finite = np.isfinite(kappa)
        self.assertTrue(np.all(finite[:, -1]))
        self.assertGreater(finite.mean(), 0.5)
        np.testing.assert_allclose(kappa[finite], 1.0 / SPHERE_RADIUS, rtol=1e-9)
        # A sphere looks the same at every scale and everywhere: no features, every point similar to the query.
        self.assertLess(np.max(sphere['GLSFeature']), 1e-9)
        self.assertLess(np.max(sphere['GLSDissimilarity']), 1e-9)
        self.assertTrue(np.all(sphere['GLSSimilar'] == 1))

    def test_pvpython_and_python3_examples_equal_the_cxx_example(self):
        if not os.path.isfile(self.output('cxx')):
            check(run([self.cxx_example(), ARGS.data, self.output('cxx'), str(QUERY)]))
        examples = os.path.join(ARGS.source, 'Examples', 'Python')
        prefix = os.path.abspath(ARGS.prefix)
        check(run([ARGS.pvpython, os.path.join(examples, 'gls_pipeline_paraview.py'), ARGS.data,
                   self.output('pvpython'), str(QUERY)],
                  env=clean_environment(PV_PLUGIN_PATH=os.path.join(prefix, 'lib', 'paraview-5.11', 'plugins'))))
        check(run([ARGS.python3, os.path.join(examples, 'gls_pipeline_vtk.py'), ARGS.data, self.output('python3'),
                   str(QUERY)],
                  env=clean_environment(PYTHONPATH=os.path.join(prefix, 'lib', 'python3', 'dist-packages'))))
        cxx = read_arrays(self.output('cxx'))
        assert_arrays_equal(self, cxx, read_arrays(self.output('pvpython')), 'pvpython vs C++ example')
        assert_arrays_equal(self, cxx, read_arrays(self.output('python3')), 'python3 vs C++ example')

    def test_examples_without_arguments_print_their_usage(self):
        prefix = os.path.abspath(ARGS.prefix)
        result = run([self.cxx_example()])
        self.assertEqual(result.returncode, 2)
        self.assertIn('usage:', result.stderr)
        result = run([ARGS.python3, os.path.join(ARGS.source, 'Examples', 'Python', 'gls_pipeline_vtk.py')],
                     env=clean_environment(PYTHONPATH=os.path.join(prefix, 'lib', 'python3', 'dist-packages')))
        self.assertEqual(result.returncode, 2)
        self.assertIn('gls_pipeline_vtk.py <input>', result.stderr)

    def test_package_rejects_another_vtk_naming_vtk_dir(self):
        fake = os.path.join(self.work, 'other-vtk')
        os.makedirs(fake, exist_ok=True)
        with open(os.path.join(fake, 'vtk-config.cmake'), 'w') as f:
            f.write('set(VTK_VERSION 9.1.0)\n')  # what Debian's libvtk9-dev would say
        result = run([ARGS.cmake, '-S', os.path.join(ARGS.source, 'Examples', 'Cxx'), '-B',
                      os.path.join(self.work, 'cxx-other-vtk'), '-DVTK_DIR=' + fake,
                      '-DCMAKE_PREFIX_PATH=' + os.path.abspath(ARGS.prefix)])
        self.assertNotEqual(result.returncode, 0)
        message = ' '.join(result.stderr.split())  # CMake wraps long messages
        self.assertIn('found VTK 9.1.0', message)
        self.assertIn('set VTK_DIR to', message)

    def test_installed_gls_analyze_runs_from_the_prefix(self):
        analyze = os.path.join(ARGS.prefix, 'bin', 'gls-analyze')
        result = check(run([analyze, '--help']))
        self.assertIn('usage: gls-analyze', result.stdout)
        out = os.path.join(self.work, 'gls-analyze')
        result = check(run([analyze, self.sphere, '--output-dir', out, '--scales', '4', '--min-scale', '0.05',
                            '--max-scale', '0.2']))
        # kappa at each point's most stable scale, written as float32 (7 significant digits).
        kappa = read_arrays(os.path.join(out, 'sphere-gls.vtp'))['GLSStableKappa']
        np.testing.assert_allclose(kappa, 1.0 / SPHERE_RADIUS, rtol=1e-6)

    def test_installed_gls_analyze_defaults_to_the_installed_scan_or_asks_for_an_input(self):
        analyze = os.path.join(ARGS.prefix, 'bin', 'gls-analyze')
        # What the wrapper hands to pvpython (a stand-in that prints it; DISPLAY set: no virtual X server).
        stand_in = os.path.join(self.work, 'stand-in')
        os.makedirs(stand_in, exist_ok=True)
        with open(os.path.join(stand_in, 'pvpython'), 'w') as f:
            f.write('#!/bin/sh\necho "$GLS_DEFAULT_INPUT|$GLS_PLUGIN|$1"\n')
        os.chmod(os.path.join(stand_in, 'pvpython'), 0o755)
        env = clean_environment(PATH=stand_in + os.pathsep + os.environ['PATH'], DISPLAY=':99')
        default_input, plugin, script = check(run([analyze], env=env)).stdout.strip().split('|')
        prefix = os.path.realpath(ARGS.prefix)
        self.assertEqual(os.path.realpath(default_input),
                         os.path.join(prefix, 'share', 'GrowingLeastSquares', 'data', 'stanford-bunny.obj'))
        self.assertTrue(os.path.isfile(default_input))
        self.assertEqual(os.path.realpath(plugin), os.path.join(
            prefix, 'lib', 'paraview-5.11', 'plugins', 'GrowingLeastSquares', 'GrowingLeastSquares.so'))
        self.assertEqual(os.path.realpath(script),
                         os.path.join(prefix, 'share', 'GrowingLeastSquares', 'python', 'gls_main.py'))
        # A prefix without the bundled data: the real job says an input is needed.
        bare = os.path.join(self.work, 'prefix-without-data')
        shutil.rmtree(bare, ignore_errors=True)
        os.makedirs(os.path.join(bare, 'share', 'GrowingLeastSquares'))
        shutil.copytree(os.path.join(ARGS.prefix, 'bin'), os.path.join(bare, 'bin'))
        shutil.copytree(os.path.join(ARGS.prefix, 'share', 'GrowingLeastSquares', 'python'),
                        os.path.join(bare, 'share', 'GrowingLeastSquares', 'python'))
        os.symlink(os.path.abspath(os.path.join(ARGS.prefix, 'lib')), os.path.join(bare, 'lib'))
        result = run([os.path.join(bare, 'bin', 'gls-analyze')])
        self.assertNotEqual(result.returncode, 0)
        self.assertIn('no input', result.stderr)


if __name__ == '__main__':
    unittest.main(argv=[sys.argv[0]] + UNITTEST_ARGV, verbosity=2)
