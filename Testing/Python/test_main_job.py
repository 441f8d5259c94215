"""The main job end to end (pvpython): gls-analyze on the bundled scan, on XYZ/CSV files, and on bad input.

    pvpython test_main_job.py <build/bin/gls-analyze> <work dir>"""
import math
import os
import shutil
import sys
import unittest

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

import main_job_helpers as helpers
from main_job_helpers import denoising_rms, failure_text, image_stats, polydata_from, read_vtp, write_sphere

ANALYZE, WORK = sys.argv[1], sys.argv[2]


def run(*args):
    return helpers.run(ANALYZE, *args)


class MainJob(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        shutil.rmtree(WORK, ignore_errors=True)
        os.makedirs(WORK)

    def test_bundled_scan_outputs_are_complete_and_non_trivial(self):
        out = os.path.join(WORK, 'bunny')
        result = run('--output-dir', out, '--noise', '0.002')
        self.assertEqual(result.returncode, 0, failure_text(result))
        self.assertIn('scale space', result.stderr)  # the progress lines
        self.assertIn('adaptive bandwidth', result.stderr)
        files = {s: os.path.join(out, 'stanford-bunny' + s) for s in
                 ('-gls.vtp', '-features.png', '-profiles.png', '-denoising.png', '-scale-space.png', '-gls.pvsm')}
        for f in files.values():
            self.assertTrue(os.path.isfile(f), f)
        pd = read_vtp(files['-gls.vtp'])
        self.assertEqual(pd.GetNumberOfPoints(), 35947)
        for name in ('Normals', 'GLSTau', 'GLSEta', 'GLSKappa', 'GLSFitness', 'GLSdTau', 'GLSdEta', 'GLSdKappa',
                     'GLSNeighborCount', 'GLSGeometricVariation', 'GLSPertinentScales', 'GLSPertinentScaleCount',
                     'GLSFeature'):
            self.assertIsNotNone(pd.GetPointData().GetArray(name), name)
        feature = vtk_to_numpy(pd.GetPointData().GetArray('GLSFeature'))
        self.assertTrue(np.all((feature >= 0) & (feature <= 1)))
        # The data-relative sigma: features stand out from a low background (median 0.28, the filter's target).
        self.assertLess(np.percentile(feature, 5), 0.15)
        self.assertLess(np.median(feature), 0.3)
        self.assertGreater(np.percentile(feature, 95), 0.6)
        self.assertGreater(feature.std(), 0.15)
        for png in (files['-features.png'], files['-profiles.png'], files['-denoising.png'],
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

    def test_xyz_with_normals_and_csv_without(self):
        xyz = os.path.join(WORK, 'sphere.xyz')
        write_sphere(xyz, 4000, 2.0, True, ' ')
        result = run(xyz, '--output-dir', WORK, '--scales', '5', '--min-scale', '0.05', '--max-scale', '0.2')
        self.assertEqual(result.returncode, 0, failure_text(result))
        pd = read_vtp(os.path.join(WORK, 'sphere-gls.vtp'))
        np.testing.assert_allclose(vtk_to_numpy(pd.GetPointData().GetArray('GLSKappa')), 0.5, atol=1e-8)
        # Points exactly on a sphere with exact normals: the projection onto the fitted spheres moves nothing.
        before, after = denoising_rms(result.stdout)
        self.assertEqual(before, 0.0)
        self.assertLess(after, 1e-9)
        self.assertIn('scale-space image: skipped (the input has no polygons', result.stdout)
        self.assertFalse(os.path.exists(os.path.join(WORK, 'sphere-scale-space.png')))
        self.assertTrue(os.path.isfile(os.path.join(WORK, 'sphere-denoising.png')))
        np.testing.assert_allclose(vtk_to_numpy(pd.GetPointData().GetArray('GLSFeature')), 0.0, atol=1e-9)

        csv = os.path.join(WORK, 'ball.csv')
        write_sphere(csv, 4000, 1.0, False, ',', header='x,y,z')
        result = run(csv, '--output-dir', WORK, '--scales', '5', '--min-scale', '0.05', '--max-scale', '0.2')
        self.assertEqual(result.returncode, 0, failure_text(result))
        pd = read_vtp(os.path.join(WORK, 'ball-gls.vtp'))
        kappa = vtk_to_numpy(pd.GetPointData().GetArray('GLSKappa'))
        self.assertLess(abs(np.median(kappa) - 1.0), 0.02)  # estimated, MST-oriented normals: outward

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
            kappa = vtk_to_numpy(out.GetPointData().GetArray('GLSKappa'))
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
        other = os.path.join(WORK, 'cloud.las')
        open(other, 'w').close()
        result = run(other)
        self.assertEqual(result.returncode, 2)
        self.assertIn('unsupported type', result.stderr)


if __name__ == '__main__':
    unittest.main(argv=[sys.argv[0]], verbosity=2)
