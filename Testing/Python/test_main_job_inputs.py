"""The main job on the inputs users bring (issue 16): each bad case ends with one error line on stderr, exit status 2
and no result files; each readable case gives the right numbers (a unit sphere: kappa = 1) and the arrays of its
columns. The catalogue is in Testing/README.md ("Real inputs").

    pvpython test_main_job_inputs.py <build/bin/gls-analyze> <work dir> <Testing/Data> [Inputs.test_name ...]"""
import os
import shutil
import sys
import unittest

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

import main_job_helpers as helpers  # (first: it makes the main job's own modules importable)
import las_writer
import gls_coincident  # noqa: E402 (the main job's own modules)
import gls_io  # noqa: E402
import gls_memory  # noqa: E402
from main_job_helpers import central_background, error_lines, failure_text, point_array, read_vtp
from shapes import sphere

ANALYZE, WORK, DATA = sys.argv[1], sys.argv[2], sys.argv[3]
QUICK = ('--scales', '5', '--min-scale', '0.05', '--max-scale', '0.2')  # a few scales: the sphere needs no more
RESULT_SUFFIXES = ('-gls.vtp', '-features.png', '-shape-index.png', '-profiles.png', '-denoising.png', '-gls.pvsm')


def run(*args):
    return helpers.run(ANALYZE, *args)


def path(name):
    return os.path.join(WORK, name)


def write_text(name, lines, first=None):
    with open(path(name), 'w') as f:
        if first is not None:
            f.write(first + '\n')
        f.write('\n'.join(lines) + '\n')
    return path(name)


def write_las(name, points, intensity, colours, compressed=False):
    """A LAS 1.2 file of point format 3 (positions to the micrometre, intensity, GPS time, RGB, every point ground);
    with `compressed`, the LAZ flag set in the format byte. Returns its path and the positions as stored."""
    stored = las_writer.write_las(path(name), points, point_format=3, scale=1e-6, classification=np.full(len(points), 2),
                                  colours=colours, intensity=intensity, compressed=compressed)
    return path(name), stored


class DistinctPositions(unittest.TestCase):
    """The coincident-point check's grouping (gls_coincident.distinct_positions) against np.unique(axis=0), the rule
    it replaced, on clouds with repeated rows, -0.0 and infinite coordinates, and through its fallback for positions
    that share a hash (forced here by a hash that maps everything to one key)."""

    @staticmethod
    def reference(points):
        _, first, inverse = np.unique(points, axis=0, return_index=True, return_inverse=True)
        order = np.argsort(first, kind='stable')
        rank = np.empty_like(order)
        rank[order] = np.arange(len(order))
        return first[order], rank[inverse.reshape(-1)]

    def check(self, points):
        first, inverse = gls_coincident.distinct_positions(points)
        expected_first, expected_inverse = self.reference(points)
        np.testing.assert_array_equal(first, expected_first)
        np.testing.assert_array_equal(inverse, expected_inverse)

    def clouds(self):
        rng = np.random.default_rng(3)
        for trial in range(12):
            n = int(rng.integers(1, 2000))
            points = rng.integers(0, 12, size=(n, 3)).astype(float) * 0.25
            points[rng.integers(0, n, size=n // 5)] *= -0.0 if trial % 2 else 1.0
            if trial % 3 == 0:
                points[rng.integers(0, n, size=3), 1] = np.inf
            yield points

    def test_equals_numpy_unique(self):
        for points in self.clouds():
            self.check(points)
        self.check(np.random.default_rng(5).random((50000, 3)).astype(np.float32).astype(float))
        # A scan's case: a few copies among many distinct rows (only the rows whose hash another shares are
        # compared), as float64 and as float32 rows.
        few = np.random.default_rng(6).random((50000, 3))
        few = np.vstack([few, few[[10, 20, 10]], [[-0.0, 0.5, 0.5], [0.0, 0.5, 0.5], [np.nan, 1, 1], [np.nan, 1, 1]]])
        self.check(few)
        self.check(few.astype(np.float32))

    def test_positions_that_share_a_hash(self):
        mixed = gls_coincident._mixed
        gls_coincident._mixed = lambda z: z * np.uint64(0)
        try:
            for points in self.clouds():
                self.check(points)
        finally:
            gls_coincident._mixed = mixed

    def test_a_row_with_a_nan_equals_no_other(self):
        rows = np.array([[np.nan, 0, 0], [np.nan, 0, 0], [1, 2, 3], [1, 2, 3], [0.0, 0, 0], [-0.0, 0, 0]])
        first, inverse = gls_coincident.distinct_positions(rows)
        np.testing.assert_array_equal(first, [0, 1, 2, 4])
        np.testing.assert_array_equal(inverse, [0, 1, 2, 2, 3, 3])

    def test_merge_releases_the_positions_and_scatter_rebuilds_them_bit_for_bit(self):
        """The merged view holds the distinct finite positions only (the input's are released while the analysis
        runs); the written cloud has the input's every position back, bit for bit (-0.0 copies included), float32
        and float64, with a result array copied to every copy; a row with a NaN coordinate is left out of the
        analysis, counted, and written back in its place with NaN coordinates and a NaN result."""
        from vtkmodules.util.numpy_support import numpy_to_vtk
        from vtkmodules.vtkCommonCore import vtkPoints
        from vtkmodules.vtkCommonDataModel import vtkPolyData
        rng = np.random.default_rng(8)
        for dtype in (np.float32, np.float64):
            rows = rng.random((500, 3)).astype(dtype)
            rows = np.vstack([rows, rows[[3, 7, 3]], np.array([[-0.0, 0.5, 0.5], [0.0, 0.5, 0.5],
                                                                 [np.nan, 1, 1]], dtype=dtype)])
            polydata = vtkPolyData()
            points = vtkPoints()
            points.SetData(numpy_to_vtk(rows.copy(), deep=True))
            polydata.SetPoints(points)
            merged = gls_coincident.merge(polydata)
            self.assertIsNotNone(merged)
            self.assertIsNone(polydata.GetPoints())
            self.assertEqual(merged.copies, 4)
            self.assertEqual(merged.non_finite, 1)
            distinct = vtk_to_numpy(merged.polydata.GetPoints().GetData())
            self.assertEqual(len(distinct), len(rows) - 4 - 1)
            self.assertTrue(np.isfinite(distinct).all())
            value = numpy_to_vtk(np.arange(len(distinct), dtype=np.float64), deep=True)
            value.SetName('Value')
            merged.polydata.GetPointData().AddArray(value)
            out = merged.scatter(merged.polydata)
            back = vtk_to_numpy(out.GetPoints().GetData())
            self.assertEqual(back.dtype, rows.dtype)
            np.testing.assert_array_equal(back[:-1].view(np.uint8), rows[:-1].view(np.uint8))
            self.assertTrue(np.isnan(back[-1]).all())  # the NaN row: NaN coordinates, its place kept
            _, inverse = gls_coincident.distinct_positions(rows)
            inverse = inverse.astype(np.int64)
            inverse[-1] = -1  # (the last row: numbering the others as before)
            np.testing.assert_array_equal(merged.inverse(), inverse)
            np.testing.assert_array_equal(merged.inverse(chunk=3), inverse)  # formed a few rows at a time
            np.testing.assert_array_equal(merged.distinct_of([len(rows) - 1, 0]), inverse[[len(rows) - 1, 0]])
            expected = inverse.astype(np.float64)
            expected[-1] = np.nan
            np.testing.assert_array_equal(point_array(out, 'Value'), expected)
            self.assertEqual(out.GetFieldData().GetArray('GLSNonFinitePoints').GetValue(0), 1)



class ProfilePoints(unittest.TestCase):
    """gls_profiles.select_profile_points against its rule written as a stable sort: the points at ranks 0, n // 2
    and n - 1 of the finite features in (value, index) order, on features with many ties and NaN."""

    def test_ranks_of_the_stable_order(self):
        import gls_profiles
        rng = np.random.default_rng(2)
        for _ in range(200):
            n = int(rng.integers(1, 60))
            feature = rng.integers(0, 4, size=n).astype(float)
            feature[rng.random(n) < 0.2] = np.nan
            feature[0] = 1.0 if not np.isfinite(feature).any() else feature[0]
            valid = np.where(np.isfinite(feature))[0]
            order = valid[np.argsort(feature[valid], kind='stable')]
            expected = {}
            for label, pid in zip(('lowest feature', 'median feature', 'highest feature'),
                                  (order[0], order[len(order) // 2], order[-1])):
                if int(pid) not in expected.values():
                    expected[label] = int(pid)
            self.assertEqual(gls_profiles.select_profile_points(feature, np.zeros(n, dtype=int)), expected)


class WrittenFileCheck(unittest.TestCase):
    """gls_outputs.check_written, the read-back of the written .vtp's header: a good file passes, a file cut short,
    one with fewer points and one without an array fail with a StageError."""

    def test_good_short_and_different_files(self):
        from vtkmodules.util.numpy_support import numpy_to_vtk
        from vtkmodules.vtkCommonCore import vtkPoints
        from vtkmodules.vtkCommonDataModel import vtkPolyData
        import gls_outputs
        import gls_watch
        os.makedirs(WORK, exist_ok=True)

        def cloud(count, arrays):
            polydata = vtkPolyData()
            points = vtkPoints()
            points.SetData(numpy_to_vtk(np.random.default_rng(1).random((count, 3)), deep=True))
            polydata.SetPoints(points)
            for name in arrays:
                values = numpy_to_vtk(np.arange(count, dtype=np.float32), deep=True)
                values.SetName(name)
                polydata.GetPointData().AddArray(values)
            return polydata
        good = cloud(100, ('GLSFeature', 'GLSStableTau'))
        vtp = path('check.vtp')
        gls_outputs.write_vtp(vtp, good)
        gls_outputs.check_written(vtp, good)
        with self.assertRaisesRegex(gls_watch.StageError, '100 points instead of 101'):
            gls_outputs.check_written(vtp, cloud(101, ('GLSFeature', 'GLSStableTau')))
        with self.assertRaisesRegex(gls_watch.StageError, 'point arrays'):
            gls_outputs.check_written(vtp, cloud(100, ('GLSFeature', 'GLSStableTau', 'GLSStableKappa')))
        with open(vtp, 'rb') as f:
            head = f.read(200)
        with open(vtp, 'wb') as f:
            f.write(head)
        with self.assertRaises(gls_watch.StageError):
            gls_outputs.check_written(vtp, good)


class Inputs(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        shutil.rmtree(WORK, ignore_errors=True)
        os.makedirs(WORK)
        cls.points, cls.normals = sphere(3000)
        cls.colours = np.rint(np.abs(cls.points) * 255).astype(int)

    def assertFailsInOneLine(self, result, expected_start, out=None, created=True):
        """Exit status 2, one error line starting with `expected_start`, no VTK message, no result file."""
        self.assertEqual(result.returncode, 2, failure_text(result))
        lines = error_lines(result)
        self.assertEqual(len(lines), 1, result.stderr)
        self.assertTrue(lines[0].startswith('gls-analyze: ' + expected_start), lines[0])
        self.assertNotIn('ERR|', result.stderr)
        self.assertNotIn('Traceback', result.stderr)
        if out is not None:
            if created:
                self.assertEqual(os.listdir(out), [], 'a failed run left files')
            else:
                self.assertFalse(os.path.exists(out), 'the output directory was created before the options failed')
        return lines[0]

    def assertSucceeds(self, result, out, stem, mesh=False):
        self.assertEqual(result.returncode, 0, failure_text(result))
        self.assertEqual(error_lines(result), [])
        expected = RESULT_SUFFIXES + (('-scale-space.png',) if mesh else ())
        self.assertEqual(sorted(os.listdir(out)), sorted(stem + s for s in expected))
        return read_vtp(os.path.join(out, stem + '-gls.vtp'))

    def assertUnitSphereKappa(self, pd):
        kappa = point_array(pd, 'GLSStableKappa')
        self.assertLess(abs(np.nanmedian(kappa) - 1.0), 0.02)  # estimated, MST-oriented normals: outward

    # Options and output directory -------------------------------------------------------------------------------

    def test_bad_options_fail_in_one_line_before_any_work(self):
        cloud = path('options.xyz')
        np.savetxt(cloud, self.points)
        cases = [(('--min-scale', '0'), '--min-scale must be a positive fraction of the diagonal; got 0'),
                 (('--min-scale', '0.1', '--max-scale', '0.05'),
                  '--max-scale must be larger than --min-scale; got --min-scale 0.1, --max-scale 0.05'),
                 (('--scales', '0'), '--scales must be at least 2'),
                 (('--sigma', '-1'), '--sigma must be positive; got -1'),
                 (('--noise', 'nan'), '--noise must be 0 or positive; got nan'),
                 (('--scales', 'x'), "argument --scales: invalid int value: 'x'")]
        for k, (options, expected) in enumerate(cases):
            out = path('options-%d' % k)
            self.assertFailsInOneLine(run(cloud, '--output-dir', out, *options), expected, out, created=False)

    def test_unwritable_output_directory(self):
        cloud = path('unwritable.xyz')
        np.savetxt(cloud, self.points)
        blocker = path('a-file')
        open(blocker, 'w').close()
        self.assertFailsInOneLine(run(cloud, '--output-dir', os.path.join(blocker, 'out')),
                                  'cannot write to the output directory %s: Not a directory'
                                  % os.path.join(blocker, 'out'))
        if os.geteuid() != 0:  # root writes anywhere
            locked = path('locked')
            os.makedirs(locked)
            os.chmod(locked, 0o555)
            self.assertFailsInOneLine(run(cloud, '--output-dir', os.path.join(locked, 'out')),
                                      'cannot write to the output directory')

    # A stage that fails stops the job ---------------------------------------------------------------------------

    def test_a_stage_error_stops_the_job_and_writes_nothing(self):
        # Valid options the features refuse (the sigma's sample at every scale, whatever the machine): the error.
        out = path('too-many-scales')
        result = run(os.path.join(DATA, 'fandisk.obj'), '--output-dir', out, '--scales', '1000000')
        line = self.assertFailsInOneLine(result, 'features and summary: Not enough memory budget', out)
        self.assertTrue(line.endswith('; no results written'), line)
        self.assertNotIn('GLS pipeline', result.stdout)
        # Scales far below the spacing: every fit undefined, so no feature: an error with the advice.
        out = path('tiny-scales')
        result = run(os.path.join(DATA, 'fandisk.obj'), '--output-dir', out, '--min-scale', '1e-9',
                     '--max-scale', '1e-8')
        line = self.assertFailsInOneLine(result, 'no point has a defined feature', out)
        self.assertIn('use larger scales', line)

    # Empty, tiny and damaged files ------------------------------------------------------------------------------

    def test_empty_tiny_and_damaged_files(self):
        empty = path('empty.ply')
        open(empty, 'w').close()
        out = path('empty-out')
        self.assertFailsInOneLine(run(empty, '--output-dir', out), '%s: the file is empty' % empty, out,
                                  created=False)

        e57 = path('scan.e57')
        with open(e57, 'wb') as f:
            f.write(b'ASTM-E57' + bytes(40))
        out = path('e57-out')
        line = self.assertFailsInOneLine(run(e57, '--output-dir', out), '%s: an E57 scan needs libE57Format' % e57,
                                         out, created=False)
        self.assertIn('pdal translate', line)

        no_vertex = path('no-vertex.ply')
        helpers.write_ply(no_vertex, helpers.polydata_from(np.zeros((0, 3))))
        out = path('no-vertex-out')
        self.assertFailsInOneLine(run(no_vertex, '--output-dir', out), '%s: no points' % no_vertex, out)

        # Truncated PLY files (ParaView's reader aborts on the ASCII one and crashes on the binary one).
        whole = helpers.polydata_from(self.points[:50], self.normals[:50])
        for binary in (False, True):
            name = path('truncated-%s.ply' % ('binary' if binary else 'ascii'))
            helpers.write_ply(name, whole, binary)
            with open(name, 'rb') as f:
                data = f.read()
            with open(name, 'wb') as f:
                f.write(data[:len(data) * 2 // 3])
            out = name + '-out'
            line = self.assertFailsInOneLine(run(name, '--output-dir', out),
                                             '%s: a damaged or truncated PLY file: ' % name, out)
            self.assertIn('vertex record', line)
        # A header whose element line gives no count (a ValueError and a traceback once, exit 1).
        malformed = path('malformed.ply')
        with open(malformed, 'w') as f:
            f.write('ply\nformat ascii 1.0\nelement vertex abc\nproperty float x\nproperty float y\n'
                    'property float z\nend_header\n0 0 0\n')
        out = path('malformed-out')
        self.assertFailsInOneLine(run(malformed, '--output-dir', out), "%s: a damaged or truncated PLY file: a "
                                  "malformed header: the header line 'element vertex abc' gives no count" % malformed,
                                  out)

        out = path('four-out')
        four = write_text('four.xyz', ['0 0 0', '1 0 0', '0 1 0', '0 0 1'])
        self.assertFailsInOneLine(run(four, '--output-dir', out), 'no point has a defined feature', out)

        out = path('one-position-out')
        same = write_text('one-position.xyz', ['1 2 3'] * 50)
        self.assertFailsInOneLine(run(same, '--output-dir', out),
                                  '%s: all 50 points are at one position: nothing to analyse' % same, out)

    # Text layouts -----------------------------------------------------------------------------------------------

    def test_xyz_rgb_colours_are_colours_not_normals(self):
        cloud = write_text('coloured.xyz', ['%.9f %.9f %.9f %d %d %d' % (*p, *c)
                                            for p, c in zip(self.points, self.colours)])
        out = path('coloured-out')
        result = run(cloud, '--output-dir', out, *QUICK)
        pd = self.assertSucceeds(result, out, 'coloured')
        self.assertIn('columns x y z r g b (6 columns, no header: 0-255 integers, so colours)', result.stdout)
        rgb = pd.GetPointData().GetArray('RGB')
        self.assertEqual(rgb.GetDataTypeAsString(), 'unsigned char')
        np.testing.assert_array_equal(vtk_to_numpy(rgb), self.colours)
        # Estimated: unit (to the file's rounding of each component to 2^-17, docs/main-job.md), along the sphere's
        # normals.
        normals = point_array(pd, 'Normals')
        np.testing.assert_allclose(np.linalg.norm(normals, axis=1), 1.0, atol=2 * 3 ** 0.5 * 2.0 ** -17)
        self.assertGreater(np.median(np.abs(np.einsum('ij,ij->i', normals, self.normals))), 0.999)
        self.assertUnitSphereKappa(pd)

        unclear = write_text('unclear.xyz', ['%.9f %.9f %.9f 0.5 0.5 0.5' % tuple(p) for p in self.points[:100]])
        out = path('unclear-out')
        line = self.assertFailsInOneLine(run(unclear, '--output-dir', out), 'reader: Cannot read the point cloud',
                                         out)
        self.assertIn('add a header line naming the columns', line)

    def test_leica_pts_with_count_line(self):
        intensity = np.arange(len(self.points)) % 4096 - 2048
        pts7 = write_text('scan.pts', ['%.9f %.9f %.9f %d %d %d %d' % (*p, i, *c)
                                       for p, i, c in zip(self.points, intensity, self.colours)],
                          first=str(len(self.points)))
        out = path('scan7-out')
        result = run(pts7, '--output-dir', out, *QUICK)
        pd = self.assertSucceeds(result, out, 'scan')
        self.assertIn('x y z intensity r g b (7 columns, no header: Leica PTS); 1 point count line', result.stdout)
        self.assertEqual(pd.GetPointData().GetArray('Intensity').GetDataTypeAsString(), 'float')
        np.testing.assert_array_equal(point_array(pd, 'Intensity'), intensity)
        np.testing.assert_array_equal(point_array(pd, 'RGB'), self.colours)
        self.assertUnitSphereKappa(pd)

        pts4 = write_text('scan4.pts', ['%.9f %.9f %.9f %d' % (*p, i) for p, i in zip(self.points, intensity)],
                          first=str(len(self.points)))
        out = path('scan4-out')
        result = run(pts4, '--output-dir', out, *QUICK)
        pd = self.assertSucceeds(result, out, 'scan4')
        np.testing.assert_array_equal(point_array(pd, 'Intensity'), intensity)
        self.assertIsNone(pd.GetPointData().GetArray('RGB'))
        self.assertUnitSphereKappa(pd)

    def test_las_lidar_file(self):
        intensity = np.arange(len(self.points)) % 4096
        las, stored = write_las('tile.las', self.points, intensity, self.colours)
        out = path('las-out')
        # A sphere is no lidar scene (its points classified ground here): the spanning tree's outward rule is asked
        # for instead of the lidar rules (test_main_job_scans.py has those).
        result = run(las, '--output-dir', out, '--orientation', 'mst', *QUICK)
        pd = self.assertSucceeds(result, out, 'tile')
        self.assertIn('LAS 1.2, point format 3, %d points' % len(self.points), result.stdout)
        np.testing.assert_allclose(vtk_to_numpy(pd.GetPoints().GetData()), stored, atol=1e-9)
        self.assertEqual(pd.GetPointData().GetArray('RGB').GetDataTypeAsString(), 'unsigned short')
        np.testing.assert_array_equal(point_array(pd, 'Intensity'), intensity)
        self.assertUnitSphereKappa(pd)
        # Scales in the data's units: the sphere's diagonal is 2 sqrt(3), so 0.1 to 0.35 absolute.
        out = path('las-absolute-out')
        result = run(las, '--output-dir', out, '--scales', '5', '--min-scale', '0.1', '--max-scale', '0.35',
                     '--absolute-scales', '--orientation', 'mst')
        self.assertSucceeds(result, out, 'tile')
        self.assertIn('5 scales from 0.1 to 0.35 (length units of the data)', result.stdout)
        self.assertFailsInOneLine(run(las, '--output-dir', path('no-lengths'), '--absolute-scales'),
                                  '--absolute-scales needs --min-scale and --max-scale', path('no-lengths'),
                                  created=False)
        laz, _ = write_las('tile.laz', self.points[:100], intensity, self.colours, compressed=True)
        out = path('laz-out')
        line = self.assertFailsInOneLine(run(laz, '--output-dir', out), 'reader: Cannot read the LAS file', out)
        self.assertIn('decompress the file first', line)
        truncated = path('truncated.las')
        with open(las, 'rb') as f, open(truncated, 'wb') as g:
            g.write(f.read()[:-10])
        out = path('truncated-out')
        line = self.assertFailsInOneLine(run(truncated, '--output-dir', out), 'reader: Cannot read the LAS file', out)
        self.assertIn('truncated, or a wrong point count', line)

    def test_the_fused_pass_is_given_what_the_budget_leaves(self):
        # gls_memory.filter_budget_mib: FILTER_SHARE of the budget less this process's resident memory (VmRSS, read
        # here on its own), at least 1 MiB; 0 (the filters' default) without a budget.
        self.assertEqual(gls_memory.filter_budget_mib(None), 0.0)
        import resource
        with open('/proc/self/statm') as f:
            rss = float(f.read().split()[1]) * resource.getpagesize()
        given = gls_memory.filter_budget_mib(rss + 1000.0 * gls_memory.MIB)
        self.assertAlmostEqual(given, gls_memory.FILTER_SHARE * 1000.0, delta=20.0)  # the RSS moves a little
        self.assertEqual(gls_memory.filter_budget_mib(rss / 2.0), 1.0)

    def test_a_file_whose_header_announces_too_many_points_is_refused_before_it_is_read(self):
        # PLY, LAS and PCD headers say how many points follow: the memory check takes that count before any reader
        # runs (no "input:" line), so a survey too large for the machine is refused in seconds, not after minutes of
        # reading. The budget: the fixed part and 2,999 points' worth (one point too few for the 3,000 here).
        n = len(self.points)
        budget = (gls_memory.FIXED_BYTES + (n - 1) * gls_memory.default_bytes_per_point(n)) / gls_memory.GIB
        ply = path('announced.ply')
        helpers.write_ply(ply, helpers.polydata_from(self.points), binary=True)
        las, _ = write_las('announced.las', self.points, np.zeros(n), self.colours)
        pcd = path('announced.pcd')
        with open(pcd, 'wb') as f:
            f.write(('VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH %d\nHEIGHT 1\n'
                     'VIEWPOINT 0 0 0 1 0 0 0\nPOINTS %d\nDATA binary\n' % (n, n)).encode() +
                    self.points.astype('<f4').tobytes())
        for cloud in (ply, las, pcd):
            self.assertEqual(gls_io.announced_point_count(cloud), n, cloud)
            out = path('announced-out')
            result = run(cloud, '--output-dir', out, '--memory-budget', '%.9f' % budget, *QUICK)
            line = self.assertFailsInOneLine(
                result, "the analysis of %d points (as the file's header announces) needs about" % n, out)
            self.assertIn('--memory-budget', line)
            self.assertNotIn('input:', result.stdout)
            # With the last point's worth more, the file is read and analysed.
            result = run(cloud, '--output-dir', out, '--memory-budget', '%.9f' % (budget + 400.0 / gls_memory.GIB),
                         *QUICK)
            self.assertSucceeds(result, out, 'announced')
            shutil.rmtree(out)
        self.assertIsNone(gls_io.announced_point_count(path('cloud.xyz')))  # text: no header count

    def test_ptx_scans_face_their_scanners(self):
        # A range scan from two positions: the upper half of the sphere seen from (0, 0, 10) with 40 missing returns,
        # the lower half from (0, 0, -10), both registered by a translation of (5, 0, 0): registered points, each
        # point's scanner position, normals facing it (outward on both halves, where the first scanner alone would
        # turn the lower half inward).
        upper = self.points[self.points[:, 2] > 0.1]
        lower = self.points[self.points[:, 2] < -0.1]
        registration = ['1 0 0 0', '0 1 0 0', '0 0 1 0', '5 0 0 1']
        lines = ['%d' % (len(upper) + 40), '1', '5 0 10', '1 0 0', '0 1 0', '0 0 1'] + registration
        lines += ['%.9f %.9f %.9f 0.5' % tuple(p) for p in upper] + ['0 0 0 0.5'] * 40
        lines += ['%d' % len(lower), '1', '5 0 -10', '1 0 0', '0 1 0', '0 0 1'] + registration
        lines += ['%.9f %.9f %.9f 0.5' % tuple(p) for p in lower]
        ptx = write_text('scan.ptx', lines)
        out = path('ptx-out')
        result = run(ptx, '--output-dir', out, *QUICK)
        pd = self.assertSucceeds(result, out, 'scan')
        self.assertIn('PTX: 2 scans, x y z intensity, 40 missing returns (0 0 0) dropped', result.stdout)
        self.assertIn("oriented automatic: towards each point's scanner", result.stdout)
        points = vtk_to_numpy(pd.GetPoints().GetData())
        np.testing.assert_allclose(points, np.vstack([upper, lower]) + [5.0, 0.0, 0.0], atol=1e-6)
        scanners = point_array(pd, 'ScannerPosition')
        np.testing.assert_array_equal(scanners, np.vstack([np.tile([5.0, 0.0, 10.0], (len(upper), 1)),
                                                           np.tile([5.0, 0.0, -10.0], (len(lower), 1))]))
        facing = np.einsum('ij,ij->i', point_array(pd, 'Normals'), scanners - points)
        self.assertEqual(np.count_nonzero(facing < 0), 0)
        outward = np.einsum('ij,ij->i', point_array(pd, 'Normals'), points - [5.0, 0.0, 0.0])
        self.assertEqual(np.count_nonzero(outward < 0), 0)

    def test_pcd_binary_compressed(self):
        # PCL's binary_compressed: the fields one after the other, LZF (here literal runs of 32 bytes at most).
        n = len(self.points)
        packed_rgb = (self.colours[:, 0].astype(np.uint32) << 16) | (self.colours[:, 1].astype(np.uint32) << 8) | \
            self.colours[:, 2].astype(np.uint32)
        plain = b''.join([self.points[:, a].astype('<f4').tobytes() for a in range(3)] +
                         [packed_rgb.astype('<u4').tobytes()])
        lzf = b''.join(bytes([len(plain[i:i + 32]) - 1]) + plain[i:i + 32] for i in range(0, len(plain), 32))
        header = ('VERSION 0.7\nFIELDS x y z rgb\nSIZE 4 4 4 4\nTYPE F F F U\nCOUNT 1 1 1 1\nWIDTH %d\n'
                  'HEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS %d\nDATA binary_compressed\n' % (n, n)).encode()
        with open(path('cloud.pcd'), 'wb') as f:
            f.write(header + np.array([len(lzf), len(plain)], '<u4').tobytes() + lzf)
        out = path('pcd-out')
        # PCL's default VIEWPOINT is a sensor at the origin, the sphere's centre: the normals would face in, so the
        # spanning tree is asked for.
        result = run(path('cloud.pcd'), '--output-dir', out, '--orientation', 'mst', *QUICK)
        pd = self.assertSucceeds(result, out, 'cloud')
        self.assertIn('PCD (binary_compressed): x y z rgb', result.stdout)
        self.assertIn('oriented minimum spanning tree', result.stdout)
        np.testing.assert_array_equal(point_array(pd, 'RGB'), self.colours)
        self.assertIsNone(pd.GetPointData().GetArray('ScannerPosition'))
        self.assertEqual(pd.GetFieldData().GetArray('ScannerPosition').GetTuple3(0), (0.0, 0.0, 0.0))
        self.assertUnitSphereKappa(pd)

    def test_semicolon_separated_decimal_commas(self):
        cloud = write_text('european.csv', [('%.9f;%.9f;%.9f' % tuple(p)).replace('.', ',') for p in self.points],
                           first='x;y;z')
        out = path('european-out')
        result = run(cloud, '--output-dir', out, *QUICK)
        pd = self.assertSucceeds(result, out, 'european')
        self.assertIn('decimal commas', result.stdout)
        np.testing.assert_allclose(vtk_to_numpy(pd.GetPoints().GetData()), self.points, atol=1e-9)
        self.assertUnitSphereKappa(pd)

    # Meshes and clouds from ParaView's readers ------------------------------------------------------------------

    def test_stl_mesh(self):
        from vtkmodules.vtkFiltersSources import vtkSphereSource
        from vtkmodules.vtkIOGeometry import vtkSTLWriter
        sphere = vtkSphereSource()
        sphere.SetRadius(2.0)
        sphere.SetThetaResolution(60)
        sphere.SetPhiResolution(40)
        writer = vtkSTLWriter()
        writer.SetFileName(path('ball.stl'))
        writer.SetInputConnection(sphere.GetOutputPort())
        writer.SetFileTypeToBinary()
        writer.Write()
        out = path('ball-out')
        pd = self.assertSucceeds(run(path('ball.stl'), '--output-dir', out, *QUICK), out, 'ball', mesh=True)
        self.assertEqual(pd.GetNumberOfPoints(), 60 * 38 + 2)  # the STL reader merges the triangles' corners
        self.assertLess(abs(np.nanmedian(point_array(pd, 'GLSStableKappa')) - 0.5), 0.01)  # radius 2

    def test_ply_cloud_without_cells_is_drawn(self):
        cloud = path('cloud.ply')
        helpers.write_ply(cloud, helpers.polydata_from(self.points, vertices=False))
        out = path('cloud-out')
        pd = self.assertSucceeds(run(cloud, '--output-dir', out, *QUICK), out, 'cloud')
        self.assertUnitSphereKappa(pd)
        # One poly-vertex cell of every point, so that the .vtp shows in ParaView (4 bytes a point, where a vertex
        # cell per point took 16).
        self.assertEqual(pd.GetNumberOfVerts(), 1)
        self.assertEqual(pd.GetVerts().GetNumberOfConnectivityIds(), pd.GetNumberOfPoints())
        # The picture shows the points (it was the background only: it drew cells, and there were none).
        self.assertLess(central_background(os.path.join(out, 'cloud-features.png')), 0.93)  # drawn: 0.90

    def test_a_stray_point_changes_nothing_and_is_not_drawn(self):
        # The sphere (radius 1) and one return 50 away: the scales and features of the clean cloud, the stray point
        # marked and left out of the picture, which frames the sphere (without that, a dot in the middle).
        clean = write_text('clean.xyz', ['%.9f %.9f %.9f' % tuple(p) for p in self.points])
        stray = write_text('stray.xyz', ['%.9f %.9f %.9f' % tuple(p) for p in self.points] + ['50 50 50'])
        a = self.assertSucceeds(run(clean, '--output-dir', path('clean-out'), *QUICK), path('clean-out'), 'clean')
        result = run(stray, '--output-dir', path('stray-out'), *QUICK)
        b = self.assertSucceeds(result, path('stray-out'), 'stray')
        self.assertIn('1 stray point', result.stderr)
        fa, fb = point_array(a, 'GLSFeature'), point_array(b, 'GLSFeature')
        self.assertTrue(np.isnan(fb[-1]))
        np.testing.assert_allclose(fb[:-1], fa, atol=1e-6)
        np.testing.assert_array_equal(point_array(b, 'GLSStray'), [0] * len(self.points) + [1])
        self.assertLess(central_background(os.path.join(path('stray-out'), 'stray-features.png')), 0.93)

    def test_obj_with_texture_coordinates(self):
        """spot.obj: 2,930 vertices split per face corner into 17,568 points by ParaView's reader. The analysis of
        the distinct positions, written back to every copy, equals the analysis of the de-duplicated mesh; the
        estimated normals agree with the mesh's (the issue measured 3.3 degrees median after merging)."""
        from vtkmodules.vtkFiltersCore import vtkCleanPolyData, vtkPolyDataNormals
        from vtkmodules.vtkIOGeometry import vtkOBJReader
        from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
        out = path('spot-out')
        result = run(os.path.join(DATA, 'spot.obj'), '--output-dir', out)
        pd = self.assertSucceeds(result, out, 'spot', mesh=True)
        self.assertIn('note: 14638 of the 17568 points coincide with an earlier one; the analysis runs on the 2930 '
                      'distinct positions', result.stdout)
        self.assertEqual(pd.GetNumberOfPoints(), 17568)
        points = vtk_to_numpy(pd.GetPoints().GetData())
        feature = point_array(pd, 'GLSFeature')
        normals = point_array(pd, 'Normals')
        _, first, inverse = np.unique(points, axis=0, return_index=True, return_inverse=True)
        inverse = inverse.reshape(-1)
        np.testing.assert_array_equal(feature, feature[first][inverse])  # every copy holds its position's values
        np.testing.assert_array_equal(normals, normals[first][inverse])

        # The same analysis on the mesh de-duplicated beforehand (vtkCleanPolyData, tolerance 0).
        reader = vtkOBJReader()
        reader.SetFileName(os.path.join(DATA, 'spot.obj'))
        clean = vtkCleanPolyData()
        clean.SetInputConnection(reader.GetOutputPort())
        clean.ToleranceIsAbsoluteOn()
        clean.SetAbsoluteTolerance(0.0)
        mesh_normals = vtkPolyDataNormals()
        mesh_normals.SetInputConnection(clean.GetOutputPort())
        mesh_normals.SplittingOff()
        mesh_normals.AutoOrientNormalsOn()
        mesh_normals.Update()
        mesh = mesh_normals.GetOutput()
        self.assertEqual(mesh.GetNumberOfPoints(), 2930)
        clean.Update()
        writer = vtkXMLPolyDataWriter()
        writer.SetFileName(path('spot-clean.vtp'))
        writer.SetInputData(clean.GetOutput())
        writer.Write()
        out_clean = path('spot-clean-out')
        reference = self.assertSucceeds(run(path('spot-clean.vtp'), '--output-dir', out_clean), out_clean,
                                        'spot-clean', mesh=True)
        ref_points = vtk_to_numpy(reference.GetPoints().GetData())
        order = {tuple(p): i for i, p in enumerate(ref_points)}
        match = np.array([order[tuple(p)] for p in points])
        np.testing.assert_allclose(feature, point_array(reference, 'GLSFeature')[match], atol=1e-9)

        mesh_order = {tuple(p): i for i, p in enumerate(vtk_to_numpy(mesh.GetPoints().GetData()))}
        expected = vtk_to_numpy(mesh.GetPointData().GetNormals())[[mesh_order[tuple(p)] for p in points[first]]]
        cosine = np.clip(np.einsum('ij,ij->i', normals[first], expected), -1, 1)
        angles = np.degrees(np.arccos(np.abs(cosine)))
        self.assertLess(np.median(angles), 6.0)
        self.assertLess(np.mean(cosine < 0), 0.01)  # flipped


if __name__ == '__main__':
    unittest.main(argv=sys.argv[:1] + sys.argv[4:], verbosity=2)
