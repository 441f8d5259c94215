"""The main job end to end (pvpython): gls-analyze on the bundled scan, on XYZ/CSV files, and on bad input.

    pvpython test_main_job.py <build/bin/gls-analyze> <work dir>"""
import math
import os
import shutil
import sys
import unittest

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

import main_job_helpers as helpers  # (first: it makes the main job's own modules importable)
import gls_memory  # noqa: E402 (the main job's own modules)
import gls_outputs  # noqa: E402
from main_job_helpers import denoising_rms, failure_text, image_stats, polydata_from, read_vtp, write_sphere

ANALYZE, WORK = sys.argv[1], sys.argv[2]


# What the default output holds besides the points (docs/main-job.md, "Outputs"), and their types in the file.
DEFAULT_ARRAYS = {'Normals': 'float', 'NormalQuality': 'float', 'GLSFeature': 'float',
                  'GLSPertinentScaleCount': 'unsigned char', 'GLSStableScale': 'float', 'GLSStableTau': 'float',
                  'GLSStableKappa': 'float', 'GLSStablePhi': 'float', 'GLSMaxVariation': 'float',
                  'GLSMaxVariationScale': 'float', 'GLSStableDirectionScale': 'float', 'GLSAnisotropy': 'float',
                  'GLSStableShapeIndex': 'float', 'GLSStableDirection': 'float'}
DIRECTION_ARRAYS = ('GLSStableDirectionScale', 'GLSAnisotropy', 'GLSStableShapeIndex', 'GLSStableDirection')
PER_SCALE_ARRAYS = ('GLSTau', 'GLSEta', 'GLSKappa', 'GLSFitness', 'GLSdTau', 'GLSdEta', 'GLSdKappa',
                    'GLSNeighborCount', 'GLSGeometricVariation', 'GLSPertinentScales')


def run(*args):
    return helpers.run(ANALYZE, *args)


def start_on_a_million_points(name, stderr):
    """(process, output folder): the job started on a 1M-point torus without a display, in a session of its own
    (os.killpg then signals it as a terminal's Ctrl-C would); stdout piped."""
    import subprocess
    ply = os.path.join(WORK, 'torus-%s.ply' % name)
    write_torus_ply(ply, 1000000)
    out = os.path.join(WORK, name)
    env = dict(os.environ)
    env.pop('DISPLAY', None)
    process = subprocess.Popen([ANALYZE, ply, '--output-dir', out], stdout=subprocess.PIPE, stderr=stderr, text=True,
                               env=env, start_new_session=True)
    return process, out


def write_torus_ply(path, count, seed=3):
    """A binary float PLY of `count` points (positions only, random order) on a torus (R 1, r 0.3)."""
    rng = np.random.default_rng(seed)
    u, v = rng.uniform(0, 2 * np.pi, count), rng.uniform(0, 2 * np.pi, count)
    points = np.stack([(1 + 0.3 * np.cos(v)) * np.cos(u), (1 + 0.3 * np.cos(v)) * np.sin(u), 0.3 * np.sin(v)], 1)
    with open(path, 'wb') as f:
        f.write(('ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n'
                 'property float z\nend_header\n' % count).encode())
        f.write(points.astype('<f4').tobytes())


class MainJob(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        shutil.rmtree(WORK, ignore_errors=True)
        os.makedirs(WORK)

    def test_bundled_scan_outputs_are_complete_and_non_trivial(self):
        out = os.path.join(WORK, 'bunny')
        result = run('--output-dir', out, '--noise', '0.002')
        self.assertEqual(result.returncode, 0, failure_text(result))
        self.assertIn('features and summary', result.stderr)  # the progress lines
        self.assertNotIn('warning', result.stderr)  # the demo warns about none of its own choices
        self.assertIn('adaptive bandwidth', result.stderr)
        files = {s: os.path.join(out, 'stanford-bunny' + s) for s in
                 ('-gls.vtp', '-features.png', '-shape-index.png', '-profiles.png', '-denoising.png',
                  '-scale-space.png', '-gls.pvsm')}
        for f in files.values():
            self.assertTrue(os.path.isfile(f), f)
        pd = read_vtp(files['-gls.vtp'])
        self.assertEqual(pd.GetNumberOfPoints(), 35947)
        for name in DEFAULT_ARRAYS:
            self.assertIsNotNone(pd.GetPointData().GetArray(name), name)
        for name in PER_SCALE_ARRAYS:  # only with --per-scale
            self.assertIsNone(pd.GetPointData().GetArray(name), name)
        feature = vtk_to_numpy(pd.GetPointData().GetArray('GLSFeature'))
        self.assertTrue(np.all((feature >= 0) & (feature <= 1)))
        # The data-relative sigma: features stand out from a low background (median 0.28, the filter's target).
        self.assertLess(np.percentile(feature, 5), 0.15)
        self.assertLess(np.median(feature), 0.3)
        self.assertGreater(np.percentile(feature, 95), 0.6)
        self.assertGreater(feature.std(), 0.15)
        self.assertIn('principal directions: ', result.stdout)
        for png in (files['-features.png'], files['-shape-index.png'], files['-profiles.png'], files['-denoising.png'],
                    files['-scale-space.png']):
            background, colours = image_stats(png)
            self.assertLess(background, 0.95, png)
            self.assertGreater(colours, 200, png)
        # Noise of 0.002 x diagonal along the normals (RMS 0.0005 here): the denoised cloud is at least twice
        # closer to the scan (measured 0.00050 -> 0.00019; the scan's own roughness is smoothed too).
        before, after = denoising_rms(result.stdout)
        diagonal = math.sqrt(sum((pd.GetBounds()[2 * a + 1] - pd.GetBounds()[2 * a]) ** 2 for a in range(3)))
        self.assertAlmostEqual(before / diagonal, 0.002, delta=0.0001)
        self.assertLess(after * 2.0, before)
        with open(files['-gls.pvsm']) as f:
            state = f.read()
        self.assertIn('XMLPolyDataReader', state)
        self.assertIn(os.path.abspath(files['-gls.vtp']), state)
        self.assertNotIn('stand-in', state)  # built on a small stand-in, the state names the written file
        from paraview import simple
        simple.LoadState(files['-gls.pvsm'])
        reader = simple.FindSource(os.path.basename(files['-gls.vtp']))
        reader.UpdatePipeline()
        self.assertEqual(reader.GetDataInformation().GetNumberOfPoints(), pd.GetNumberOfPoints())
        self.assertEqual(list(reader.GetDataInformation().GetBounds()), list(pd.GetBounds()))
        self.assertEqual(simple.GetDisplayProperties(reader).ColorArrayName[1], 'GLSFeature')
        simple.ResetSession()

    def test_xyz_with_normals_and_csv_without(self):
        xyz = os.path.join(WORK, 'sphere.xyz')
        write_sphere(xyz, 4000, 2.0, True, ' ')
        result = run(xyz, '--output-dir', WORK, '--scales', '5', '--min-scale', '0.05', '--max-scale', '0.2')
        self.assertEqual(result.returncode, 0, failure_text(result))
        pd = read_vtp(os.path.join(WORK, 'sphere-gls.vtp'))
        # Exact points and normals: kappa 1/2 at every scale, so at the most stable one too (float32 in the file).
        np.testing.assert_allclose(vtk_to_numpy(pd.GetPointData().GetArray('GLSStableKappa')), 0.5, atol=1e-6)
        # Points exactly on a sphere with exact normals: the projection onto the fitted spheres moves nothing.
        before, after = denoising_rms(result.stdout)
        self.assertEqual(before, 0.0)
        self.assertLess(after, 1e-9)
        self.assertIn('scale-space image: skipped (the input has no polygons', result.stdout)
        self.assertFalse(os.path.exists(os.path.join(WORK, 'sphere-scale-space.png')))
        self.assertTrue(os.path.isfile(os.path.join(WORK, 'sphere-denoising.png')))
        np.testing.assert_allclose(vtk_to_numpy(pd.GetPointData().GetArray('GLSFeature')), 0.0, atol=1e-9)
        # A sphere is umbilic at every scale: no steadiest principal direction anywhere (NaN), the picture all grey.
        for name in DIRECTION_ARRAYS:
            self.assertTrue(np.all(np.isnan(vtk_to_numpy(pd.GetPointData().GetArray(name)))), name)
        self.assertTrue(os.path.isfile(os.path.join(WORK, 'sphere-shape-index.png')))

        csv = os.path.join(WORK, 'ball.csv')
        write_sphere(csv, 4000, 1.0, False, ',', header='x,y,z')
        result = run(csv, '--output-dir', WORK, '--scales', '5', '--min-scale', '0.05', '--max-scale', '0.2',
                     '--no-directions')
        self.assertEqual(result.returncode, 0, failure_text(result))
        self.assertNotIn('principal directions', result.stdout)
        self.assertFalse(os.path.exists(os.path.join(WORK, 'ball-shape-index.png')))
        pd = read_vtp(os.path.join(WORK, 'ball-gls.vtp'))
        for name in DIRECTION_ARRAYS:
            self.assertIsNone(pd.GetPointData().GetArray(name), name)
        kappa = vtk_to_numpy(pd.GetPointData().GetArray('GLSStableKappa'))
        self.assertLess(abs(np.median(kappa) - 1.0), 0.02)  # estimated, MST-oriented normals: outward

    def test_per_scale_keeps_every_scale_and_the_same_summary(self):
        xyz = os.path.join(WORK, 'scales.xyz')
        write_sphere(xyz, 3000, 1.0, False, ' ')
        quick = ('--scales', '5', '--min-scale', '0.05', '--max-scale', '0.2')
        summary_dir, per_scale_dir = os.path.join(WORK, 'summary'), os.path.join(WORK, 'per-scale')
        full_dir = os.path.join(WORK, 'full-precision')
        result = run(xyz, '--output-dir', summary_dir, '--query', '7', *quick)
        self.assertEqual(result.returncode, 0, failure_text(result))
        run_output = result.stdout
        result = run(xyz, '--output-dir', per_scale_dir, '--per-scale', *quick)
        self.assertEqual(result.returncode, 0, failure_text(result))
        summary = read_vtp(os.path.join(summary_dir, 'scales-gls.vtp'))
        per_scale = read_vtp(os.path.join(per_scale_dir, 'scales-gls.vtp'))
        for name in PER_SCALE_ARRAYS:  # every scale's values (three pertinent scales at most)
            components = per_scale.GetPointData().GetArray(name).GetNumberOfComponents()
            self.assertEqual(components, 3 if name == 'GLSPertinentScales' else 15 if 'Eta' in name else 5, name)
        # --query: a sphere looks the same everywhere, and the query point is exactly like itself.
        dissimilarity = vtk_to_numpy(summary.GetPointData().GetArray('GLSDissimilarity'))
        self.assertEqual(summary.GetPointData().GetArray('GLSDissimilarity').GetDataTypeAsString(), 'float')
        self.assertEqual(dissimilarity[7], 0.0)
        self.assertLess(np.nanmax(dissimilarity), 1e-3)
        self.assertEqual(run(xyz, '--output-dir', summary_dir, '--query', '3000', *quick).returncode, 2)
        # The summary of the stored scales is the fused pass's: float32 of the same doubles with --full-precision,
        # rounded to the documented mantissa bits by default (within 2^-13 relative of the doubles).
        result = run(xyz, '--output-dir', full_dir, '--full-precision', *quick)
        self.assertEqual(result.returncode, 0, failure_text(result))
        self.assertIn('rounded to a relative 1.2e-4', run_output)
        full = read_vtp(os.path.join(full_dir, 'scales-gls.vtp'))
        for name in ('GLSFeature', 'GLSStableKappa', 'GLSStableScale', 'GLSMaxVariation', 'Normals'):
            doubles = vtk_to_numpy(per_scale.GetPointData().GetArray(name))
            np.testing.assert_array_equal(vtk_to_numpy(full.GetPointData().GetArray(name)),
                                          doubles.astype(np.float32), name)
            bits = gls_outputs.SUMMARY_MANTISSA_BITS.get(name, 23)
            rounded = vtk_to_numpy(summary.GetPointData().GetArray(name))
            np.testing.assert_array_equal(rounded, gls_outputs.rounded_float32(doubles, bits), name)
            finite = np.isfinite(doubles) & (doubles != 0)
            self.assertLessEqual(np.max(np.abs(rounded[finite] / doubles[finite] - 1)), 2.0 ** -(bits + 1) + 1e-7)

    def test_a_million_points_give_compact_summaries(self):
        import resource
        ply = os.path.join(WORK, 'torus-1m.ply')
        write_torus_ply(ply, 1000000)
        out = os.path.join(WORK, 'million')
        before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
        result = run(ply, '--output-dir', out)
        self.assertEqual(result.returncode, 0, failure_text(result))
        # The memory check's estimate covers the job's peak (the largest process of this test's children so far:
        # this test runs first).
        peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
        self.assertGreater(peak, before)
        self.assertLessEqual(peak * 1024.0, gls_memory.needed_bytes(1000000, 20, False))
        vtp = os.path.join(out, 'torus-1m-gls.vtp')
        pd = read_vtp(vtp)
        self.assertEqual(pd.GetNumberOfPoints(), 1000000)
        names = {pd.GetPointData().GetArrayName(i) for i in range(pd.GetPointData().GetNumberOfArrays())}
        self.assertEqual(names, set(DEFAULT_ARRAYS))
        for name, kind in DEFAULT_ARRAYS.items():
            self.assertEqual(pd.GetPointData().GetArray(name).GetDataTypeAsString(), kind, name)
        self.assertEqual(pd.GetPoints().GetData().GetDataTypeAsString(), 'float')
        # 12 bytes of positions, 12 of normals and 8 float32 summaries, the rounded ones' low bits zero,
        # zlib-compressed, one poly-vertex cell: at most 40 bytes a point on points in random order (issue 40; with
        # --no-directions), and 6 float32 values of the principal directions: 13 more (measured 50.8 in all).
        size = os.path.getsize(vtp) / 1e6
        self.assertLessEqual(size, 53.0)
        self.assertIn('%.1f bytes per point' % size, result.stdout)
        # A torus of tube radius 0.3: kappa at the most stable scale is about the mean curvature, between the outer
        # (1/0.3 + 1/1.3) / 2 = 2.05 and the inner (1/0.3 - 1/0.7) / 2 = 0.95 equators' (a ball of radius t on the
        # inner side reaches across the hole's curvature: 0.89 at the 1st percentile here).
        kappa = vtk_to_numpy(pd.GetPointData().GetArray('GLSStableKappa'))
        self.assertGreater(np.nanpercentile(kappa, 1), (1 / 0.3 - 1 / 0.7) / 2 - 0.1)
        self.assertLess(np.nanpercentile(kappa, 99), (1 / 0.3 + 1 / 1.3) / 2 + 0.1)
        self.assertAlmostEqual(np.nanmedian(kappa), 1 / 0.3 / 2 + 0.0, delta=0.25)
        # Its principal curvatures are 1/0.3 around the tube and cos v / (1 + 0.3 cos v) along it (v: the angle
        # around the tube): at each point's steadiest scale, the shape index (2/pi) atan((k1 + k2) / (k1 - k2))
        # (measured: p99 error 0.035) and d1 along the tube's cross-section (p99 0.66 degree).
        points = vtk_to_numpy(pd.GetPoints().GetData()).astype(float)
        u = np.arctan2(points[:, 1], points[:, 0])
        v = np.arctan2(points[:, 2], np.hypot(points[:, 0], points[:, 1]) - 1.0)
        k1, k2 = 1 / 0.3, np.cos(v) / (1 + 0.3 * np.cos(v))
        shape = vtk_to_numpy(pd.GetPointData().GetArray('GLSStableShapeIndex'))
        self.assertLess(np.percentile(np.abs(shape - 2 / np.pi * np.arctan((k1 + k2) / (k1 - k2))), 99), 0.06)
        direction = vtk_to_numpy(pd.GetPointData().GetArray('GLSStableDirection'))
        around = np.stack([-np.sin(v) * np.cos(u), -np.sin(v) * np.sin(u), np.cos(v)], axis=1)
        cosine = np.abs((direction * around).sum(axis=1))
        self.assertGreater(np.percentile(cosine, 1), math.cos(math.radians(2.0)))

    def test_per_scale_beyond_the_budget_is_refused_before_any_stage(self):
        out = os.path.join(WORK, 'refused')
        result = run('--output-dir', out, '--per-scale', '--memory-budget', '0.9')
        self.assertEqual(result.returncode, 2, failure_text(result))
        # 0.9 GiB: the fixed part and the summaries fit, every scale's arrays do not, 7 scales of them would.
        per_point = gls_memory.default_bytes_per_point(35947)
        fitting = int(((0.9 * gls_memory.GIB - gls_memory.FIXED_BYTES) / 35947 - per_point)
                      // gls_memory.PER_SCALE_BYTES_PER_POINT_SCALE)
        self.assertEqual(fitting, 7)
        self.assertIn('gls-analyze: storing every scale (--per-scale) of 35947 points at 20 scales needs about 1.0 '
                      'GiB, above the 0.9 GiB --memory-budget: drop --per-scale (the per-point summaries need about '
                      '0.8 GiB), or keep it with --scales 7', result.stderr)
        self.assertNotIn('%', result.stderr)  # no stage reported progress
        self.assertEqual(os.listdir(out), [])
        # Below what the summaries need too: no advice to drop --per-scale.
        result = run('--output-dir', out, '--per-scale', '--memory-budget', '0.5')
        self.assertEqual(result.returncode, 2, failure_text(result))
        self.assertIn('gls-analyze: the analysis of 35947 points needs about 0.8 GiB, above the 0.5 GiB '
                      '--memory-budget', result.stderr)
        self.assertNotIn('drop --per-scale', result.stderr)
        self.assertEqual(os.listdir(out), [])

    def test_ctrl_c_stops_within_seconds_and_writes_nothing(self):
        import re
        import signal
        import subprocess
        import time
        process, out = start_on_a_million_points('interrupted', subprocess.PIPE)
        seen, running = '', False
        for line in process.stderr:  # wait until the fused pass has reported a step short of its end
            seen += line
            step = re.match(r'\s*features and summary\s+(\d+)%', line)
            if step and 0 < int(step.group(1)) < 100:
                running = True
                break
        self.assertTrue(running, 'the fused pass never reported progress:\n' + seen)
        interrupted = time.time()
        os.killpg(process.pid, signal.SIGINT)  # as a terminal's Ctrl-C: the whole process group
        output, rest = process.communicate(timeout=60)
        self.assertLess(time.time() - interrupted, 10.0, seen + rest)
        self.assertEqual(process.returncode, 130, seen + rest)
        self.assertIn('gls-analyze: interrupted; no results written', rest)
        self.assertNotIn('GLS pipeline', output)  # it stopped in the fused pass, not after it
        self.assertEqual(os.listdir(out), [])  # neither results nor the staging folder

    def test_ctrl_c_while_the_data_are_written_stops_the_writer_and_writes_nothing(self):
        import signal
        import subprocess
        import time
        process, out = start_on_a_million_points('interrupted-writing', subprocess.DEVNULL)
        seen = ''
        for line in process.stdout:  # the job prints this line, then starts writing the .vtp in the background
            seen += line
            if line.startswith('output: per-point summaries'):
                break
        self.assertIn('output: per-point summaries', seen)
        interrupted = time.time()
        os.killpg(process.pid, signal.SIGINT)
        rest, _ = process.communicate(timeout=60)
        # The writer dies at once; the job stops once the call it is in returns: at worst the features picture's
        # render of the million points (software OpenGL under Xvfb, its first: 0.2-0.3 s after the interrupt on an
        # idle machine, 7-12 s with both cores busy, as under CI's parallel tests, for this code and the code before
        # the principal directions alike).
        self.assertLess(time.time() - interrupted, 20.0, seen + rest)
        self.assertEqual(process.returncode, 130, seen + rest)
        self.assertNotIn('wrote ', seen + rest)
        self.assertEqual(os.listdir(out), [])
        for _ in range(50):  # the job, its writer and its X server are gone
            try:
                os.killpg(process.pid, 0)
            except ProcessLookupError:
                break
            time.sleep(0.1)
        else:
            self.fail('a process of the interrupted job is still running')

    def test_background_write_is_the_direct_write_and_reports_a_failure(self):
        points = np.random.default_rng(5).normal(size=(5000, 3))
        pd = polydata_from(points, None)
        direct, background = os.path.join(WORK, 'direct.vtp'), os.path.join(WORK, 'background.vtp')
        # A polydata of its own: a write caches the arrays' ranges in them, and the next write stores those too.
        gls_outputs.write_vtp(direct, polydata_from(points, None))
        writing = gls_outputs.BackgroundWrite(background, pd)
        writing.finish()
        with open(direct, 'rb') as a, open(background, 'rb') as b:
            self.assertEqual(a.read(), b.read())
        failing = gls_outputs.BackgroundWrite(os.path.join(WORK, 'no-such-folder', 'x.vtp'), pd)
        with self.assertRaisesRegex(gls_outputs.OutputError, 'cannot write .*no-such-folder'):
            failing.finish()
        cancelled = gls_outputs.BackgroundWrite(os.path.join(WORK, 'cancelled.vtp'), pd)
        cancelled.cancel()
        cancelled.finish()  # nothing left to wait for

    def test_ply_and_vtp_inputs(self):
        from vtkmodules.vtkIOPLY import vtkPLYWriter
        from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
        points_file = os.path.join(WORK, 'sphere-src.xyz')
        write_sphere(points_file, 3000, 1.0, True, ' ')
        data = np.loadtxt(points_file)
        pd = polydata_from(data[:, :3], data[:, 3:])
        ply = os.path.join(WORK, 'ply-sphere.ply')
        w = vtkPLYWriter()
        w.SetFileName(ply)
        w.SetInputData(pd)
        w.Write()
        vtp = os.path.join(WORK, 'vtp-sphere.vtp')
        w2 = vtkXMLPolyDataWriter()
        w2.SetFileName(vtp)
        w2.SetInputData(pd)
        w2.SetDataModeToBinary()
        w2.Write()
        for path, stem in ((ply, 'ply-sphere'), (vtp, 'vtp-sphere')):
            result = run(path, '--output-dir', WORK, '--scales', '4', '--min-scale', '0.08', '--max-scale', '0.3')
            self.assertEqual(result.returncode, 0, failure_text(result))
            out = read_vtp(os.path.join(WORK, stem + '-gls.vtp'))
            kappa = vtk_to_numpy(out.GetPointData().GetArray('GLSStableKappa'))
            self.assertLess(abs(np.nanmedian(kappa) - 1.0), 0.02, path)

    def test_missing_unreadable_and_malformed_files_get_clear_messages(self):
        result = run(os.path.join(WORK, 'nope.ply'))
        self.assertEqual(result.returncode, 2)
        self.assertIn('no such file', result.stderr)
        bad = os.path.join(WORK, 'bad.xyz')
        with open(bad, 'w') as f:
            f.write('1 2 3\n4 5\n')
        result = run(bad)
        self.assertEqual(result.returncode, 2)
        self.assertIn('expected 3 columns', result.stderr)
        other = os.path.join(WORK, 'cloud.dxf')
        with open(other, 'w') as f:
            f.write('0\nSECTION\n')
        result = run(other)
        self.assertEqual(result.returncode, 2)
        self.assertIn('unsupported type', result.stderr)
        damaged = os.path.join(WORK, 'cloud.las')
        with open(damaged, 'w') as f:
            f.write('not a LAS file, but its name says so: long enough for a header to be read ' * 4)
        result = run(damaged)
        self.assertEqual(result.returncode, 2)
        self.assertIn("not a LAS file (it does not begin with 'LASF'; by its content text)", result.stderr)


if __name__ == '__main__':
    unittest.main(argv=[sys.argv[0]], verbosity=2)
