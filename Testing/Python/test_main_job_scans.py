"""The main job on scanners' files as they come (issue 59), each written here from its format's specification: an
organized depth-camera PCD with rows of NaN and infinities (missing returns), an airborne LAS strip (returns, scan
angles, classes, withheld points, a coordinate system), a terrestrial room scan exported as LAS, a PDAL-style PCD;
and the messages and leftovers of what goes wrong. Oracles: the side each normal must face (the sensor's, the sky's,
the room's), the integers written to the file, the counts of what was left out.

    pvpython test_main_job_scans.py <build/bin/gls-analyze> <work dir> [Scans.test_name ...]"""
import os
import shutil
import signal
import subprocess
import sys
import time
import unittest

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

import main_job_helpers as helpers  # (first: it makes the main job's own modules importable)
import las_writer
import gls_outputs  # noqa: E402 (the main job's own modules)
import gls_render  # noqa: E402
from main_job_helpers import central_background, error_lines, failure_text, point_array, read_ply, read_vtp

ANALYZE, WORK = sys.argv[1], sys.argv[2]
QUICK = ('--scales', '6')
WKT = 'PROJCS["WGS 84 / UTM zone 32N",GEOGCS["WGS 84"],UNIT["metre",1]]'


def run(*args, **kwargs):
    return helpers.run(ANALYZE, *args, **kwargs)


def path(name):
    return os.path.join(WORK, name)


def field_value(polydata, name):
    array = polydata.GetFieldData().GetAbstractArray(name)
    return None if array is None else array.GetVariantValue(0)


def depth_camera_scene(width=160, height=120, seed=1):
    """An organized depth-camera frame (PCL's camera frame: x right, y down, z forward, the sensor at the origin):
    a wall at z = 3, a floor at y = 1, a ball of radius 0.45 at (0.2, 0.3, 2.2); every 7th row and 12% of the other
    pixels are missing returns (NaN), and two pixels hold an infinite coordinate. Returns (points width*height x 3,
    true normals facing the sensor, the missing mask)."""
    rng = np.random.default_rng(seed)
    u, v = np.meshgrid(np.linspace(-0.5, 0.5, width), np.linspace(-0.38, 0.38, height))
    rays = np.stack([u.ravel(), v.ravel(), np.ones(u.size)], axis=1)
    rays /= np.linalg.norm(rays, axis=1)[:, None]
    t = np.full(len(rays), np.inf)
    normals = np.zeros_like(rays)
    wall = 3.0 / rays[:, 2]
    t, normals[:] = wall, [0.0, 0.0, -1.0]
    with np.errstate(divide='ignore'):
        floor = np.where(rays[:, 1] > 0, 1.0 / rays[:, 1], np.inf)
    hit = floor < t
    t[hit], normals[hit] = floor[hit], [0.0, -1.0, 0.0]
    centre, radius = np.array([0.2, 0.3, 2.2]), 0.45
    b = rays @ centre
    disc = b ** 2 - (centre @ centre - radius ** 2)
    ball = np.where(disc > 0, b - np.sqrt(np.maximum(disc, 0)), np.inf)
    hit = ball < t
    t[hit] = ball[hit]
    points = rays * t[:, None]
    normals[hit] = (points[hit] - centre) / radius
    points += rng.normal(0.0, 0.0015, points.shape) * (t[:, None] / 3.0)
    missing = rng.random(len(points)) < 0.12
    missing |= (np.arange(len(points)) // width) % 7 == 3
    points[missing] = np.nan
    points[[5, 20000 % len(points)], 0] = np.inf
    missing[[5, 20000 % len(points)]] = True
    return points, normals, missing


def write_pcd(file, points, width, height, fields='x y z', viewpoint='0 0 0 1 0 0 0', extra=None):
    """A binary PCD 0.7 of float fields (x y z, then `extra` columns)."""
    columns = [points] + ([] if extra is None else [extra.reshape(len(points), -1)])
    data = np.hstack(columns).astype('<f4')
    n = data.shape[1]
    header = ('# .PCD v0.7\nVERSION 0.7\nFIELDS %s\nSIZE %s\nTYPE %s\nCOUNT %s\nWIDTH %d\nHEIGHT %d\nVIEWPOINT %s\n'
              'POINTS %d\nDATA binary\n' % (fields, ' '.join(['4'] * n), ' '.join(['F'] * n), ' '.join(['1'] * n),
                                            width, height, viewpoint, len(points)))
    with open(file, 'wb') as f:
        f.write(header.encode() + data.tobytes())


def aerial_strip(seed=3):
    """A 60 m x 60 m airborne strip at about 4 points per m^2 seen from a flight line along y at x = 30 (scan angle
    from nadir to each point): rolling ground (class 2), two flat-roofed buildings with wall points (class 6), trees
    (class 5, two returns), and noise points below the ground flagged withheld (class 7). Returns (points, true normals
    (NaN for trees and noise), scan angles, returns, classes, withheld)."""
    rng = np.random.default_rng(seed)
    points, normals, classes = [], [], []

    def ground(x, y):
        return 100.0 + 2.0 * np.sin(x / 15.0) * np.cos(y / 20.0)

    buildings = [(10.0, 10.0, 22.0, 20.0, 6.0), (35.0, 38.0, 50.0, 52.0, 9.0)]  # x0, y0, x1, y1, height
    for x, y in rng.random((14400, 2)) * 60.0:
        inside = [b for b in buildings if b[0] < x < b[2] and b[1] < y < b[3]]
        if inside:
            points.append((x, y, ground(x, y) + inside[0][4]))
            normals.append((0.0, 0.0, 1.0))
            classes.append(6)
        elif ((x - 45.0) ** 2 + (y - 15.0) ** 2) < 16.0:
            points.append((x, y, ground(x, y) + 6.0 + 5.0 * rng.random()))
            normals.append((np.nan, np.nan, np.nan))
            classes.append(5)
        else:
            gx = 2.0 / 15.0 * np.cos(x / 15.0) * np.cos(y / 20.0)
            gy = -2.0 / 20.0 * np.sin(x / 15.0) * np.sin(y / 20.0)
            n = np.array([-gx, -gy, 1.0])
            points.append((x, y, ground(x, y)))
            normals.append(tuple(n / np.linalg.norm(n)))
            classes.append(2)
    # Walls: the swath's oblique rays see the walls facing the flight line (x = 30), 4 points per m^2.
    for x0, y0, x1, y1, h in buildings:
        for face in ((x0, 'x', -1.0), (x1, 'x', 1.0), (y0, 'y', -1.0), (y1, 'y', 1.0)):
            at, axis, side = face
            length = (y1 - y0) if axis == 'x' else (x1 - x0)
            for s, z in zip(rng.random(int(4 * length * h)), rng.random(int(4 * length * h))):
                if axis == 'x':
                    x, y, n = at, y0 + s * (y1 - y0), (side, 0.0, 0.0)
                else:
                    x, y, n = x0 + s * (x1 - x0), at, (0.0, side, 0.0)
                points.append((x, y, ground(x, y) + z * h))
                normals.append(n)
                classes.append(6)
    points = np.array(points) + rng.normal(0.0, 0.02, (len(points), 3)) * [[0, 0, 1]]
    normals = np.array(normals)
    classes = np.array(classes)
    returns = np.ones((len(points), 2), dtype=int)
    returns[classes == 5] = [1, 2]
    noise = 30
    points = np.vstack([points, np.column_stack([rng.random((noise, 2)) * 60.0, np.full(noise, 80.0)])])
    normals = np.vstack([normals, np.full((noise, 3), np.nan)])
    classes = np.concatenate([classes, np.full(noise, 7)])
    returns = np.vstack([returns, np.ones((noise, 2), dtype=int)])
    withheld = classes == 7
    angle = np.degrees(np.arctan2(points[:, 0] - 30.0, 600.0))  # the aircraft 600 m up
    return points + [652000.0, 5410000.0, 0.0], normals, angle, returns, classes, withheld


def room(spacing=0.08, seed=4):
    """A room 8 m x 6 m x 3 m scanned from inside (floor, walls, ceiling), true normals facing into the room."""
    rng = np.random.default_rng(seed)
    points, normals = [], []
    size = np.array([8.0, 6.0, 3.0])
    for axis in range(3):
        for end in (0.0, 1.0):
            a, b = [k for k in range(3) if k != axis]
            na, nb = int(size[a] / spacing), int(size[b] / spacing)
            grid = np.stack(np.meshgrid((np.arange(na) + 0.5) / na, (np.arange(nb) + 0.5) / nb), -1).reshape(-1, 2)
            face = np.zeros((len(grid), 3))
            face[:, a], face[:, b] = grid[:, 0] * size[a], grid[:, 1] * size[b]
            face[:, axis] = end * size[axis] + rng.normal(0.0, 0.002, len(grid))
            n = np.zeros(3)
            n[axis] = 1.0 if end == 0.0 else -1.0
            points.append(face)
            normals.append(np.tile(n, (len(grid), 1)))
    return np.vstack(points) + [10.0, 20.0, 30.0], np.vstack(normals)


def cloudcompare_scalar_fields(ply, asc):
    """The scalar fields CloudCompare 2.11 loads from `ply`: it opens the file without a window and saves it as
    text with a header line naming its columns."""
    subprocess.run(['CloudCompare', '-SILENT', '-NO_TIMESTAMP', '-AUTO_SAVE', 'OFF', '-O', ply, '-C_EXPORT_FMT', 'ASC',
                    '-ADD_HEADER', '-SAVE_CLOUDS', 'FILE', asc], check=True, capture_output=True, timeout=300,
                   env=dict(os.environ, QT_QPA_PLATFORM='offscreen'))
    with open(asc) as f:
        return f.readline().lstrip('/').split()


class Scans(unittest.TestCase):

    def assertSucceeds(self, result, out, name):
        self.assertEqual(result.returncode, 0, failure_text(result))
        return read_vtp(os.path.join(out, name + '-gls.vtp'))

    def test_an_organized_depth_camera_frame_with_missing_returns(self):
        # PCL's office1.pcd crashed the pictures (52,744 NaN points of 307,200). Here: every row kept in its place
        # (the organized layout), the missing ones counted once and NaN in every result, the normals facing PCL's
        # sensor at the default VIEWPOINT's origin, every summary line finite, pictures that show the scene.
        points, truth, missing = depth_camera_scene()
        pcd = path('frame.pcd')
        write_pcd(pcd, points, 160, 120)
        out = path('frame-out')
        result = run(pcd, '--output-dir', out, *QUICK)
        pd = self.assertSucceeds(result, out, 'frame')
        gaps = int(missing.sum())
        self.assertIn('(19200 points, %d of them with a non-finite coordinate (missing returns)' % gaps, result.stdout)
        self.assertIn('organized 160 x 120', result.stdout)
        self.assertIn('oriented automatic: towards the sensor at (0, 0, 0)', result.stdout)
        rms = helpers.denoising_rms(result.stdout)
        self.assertTrue(np.isfinite(rms).all(), rms)  # "nan -> nan" when some normals were NaN
        self.assertRegex(result.stdout, r'feature in \[\d\.\d+, \d\.\d+\], median \d\.\d+')
        self.assertRegex(result.stdout, r'a steadiest direction at \d+\.\d% of the points')
        self.assertEqual(pd.GetNumberOfPoints(), 19200)
        self.assertEqual(field_value(pd, 'GLSNonFinitePoints').ToInt(), gaps)
        written = vtk_to_numpy(pd.GetPoints().GetData()).astype(float)
        self.assertTrue(np.isnan(written[missing]).all())  # their rows: NaN coordinates (no infinity in a bound)
        np.testing.assert_array_equal(written[~missing], points[~missing].astype(np.float32))
        self.assertTrue(np.isfinite(pd.GetBounds()).all())
        normals = point_array(pd, 'Normals').astype(float)
        feature = point_array(pd, 'GLSFeature')
        self.assertTrue(np.isnan(normals[missing]).all() and np.isnan(feature[missing]).all())
        kept = ~missing & np.isfinite(normals).all(axis=1)
        self.assertGreater(kept.sum(), 0.99 * (~missing).sum())
        facing = np.einsum('ij,ij->i', normals[kept], -written[kept])
        self.assertGreaterEqual(np.mean(facing > 0), 0.999)
        for picture in ('-features.png', '-shape-index.png', '-denoising.png'):
            self.assertLess(central_background(os.path.join(out, 'frame' + picture)), 0.9, picture)

    def test_an_airborne_strip_faces_up_keeps_its_positions_and_its_coordinate_system(self):
        points, truth, angle, returns, classes, withheld = aerial_strip()
        las = path('strip.las')
        stored = las_writer.write_las(las, points, point_format=6, scale=0.001, returns=returns, scan_angle=angle,
                                      classification=classes, withheld=withheld,
                                      records=[las_writer.projection_wkt_record(WKT)])
        out = path('strip-out')
        result = run(las, '--output-dir', out, *QUICK)
        pd = self.assertSucceeds(result, out, 'strip')
        self.assertIn('(%d withheld, left out)' % withheld.sum(), result.stdout)
        self.assertIn('coordinate system: WKT', result.stdout)
        self.assertIn('oriented automatic: up, the walls along the minimum spanning tree: airborne lidar',
                      result.stdout)
        kept = ~withheld
        self.assertEqual(pd.GetNumberOfPoints(), kept.sum())
        # The file's positions, exactly: its integers times its scale plus its offset, in doubles.
        written = vtk_to_numpy(pd.GetPoints().GetData())
        self.assertEqual(written.dtype, np.float64)
        np.testing.assert_array_equal(written, stored[kept])
        self.assertEqual(field_value(pd, 'CoordinateSystemWKT').ToString(), WKT)
        self.assertEqual(field_value(pd, 'GLSWithheldPoints').ToInt(), withheld.sum())
        normals = point_array(pd, 'Normals').astype(float)
        truth, cls = truth[kept], classes[kept]
        ground = (cls == 2) & np.isfinite(normals).all(axis=1)
        self.assertGreaterEqual(np.mean(normals[ground, 2] > 0), 0.999)
        walls = (cls == 6) & (np.abs(truth[:, 2]) < 0.1) & np.isfinite(normals).all(axis=1)
        self.assertGreater(walls.sum(), 500)
        outward = np.mean(np.einsum('ij,ij->i', normals[walls], truth[walls]) > 0)
        print('airborne strip: ground %.3f%% up, walls %.1f%% outward' % (100 * np.mean(normals[ground, 2] > 0),
                                                                          100 * outward))
        self.assertGreaterEqual(outward, 0.95)
        # The state opens on the data, not on ParaView's default camera at the origin.
        with open(os.path.join(out, 'strip-gls.pvsm')) as f:
            state = f.read()
        focal = self.camera(state, 'CameraFocalPoint')
        low, high = written.min(axis=0), written.max(axis=0)
        self.assertTrue(np.all(focal >= low - 1.0) and np.all(focal <= high + 1.0), focal)
        distance = np.linalg.norm(self.camera(state, 'CameraPosition') - focal)
        self.assertLess(distance, 10.0 * np.linalg.norm(high - low))

    def test_results_as_las_and_ply_for_the_other_tools(self):
        # --output-format las,ply,vtp: the LAS file holds the input's own integers, scale, offset, attributes and
        # coordinate system with every GLS array as an Extra Bytes field; the PLY file every GLS array as a scalar
        # field; both read here from their specifications, the PLY also by CloudCompare (a peer, when installed).
        points, _, angle, returns, classes, withheld = aerial_strip(seed=5)
        las = path('tile.las')
        intensity = np.arange(len(points)) % 4000
        las_writer.write_las(las, points, point_format=6, scale=0.01, returns=returns, scan_angle=angle,
                             classification=classes, withheld=withheld, intensity=intensity,
                             records=[las_writer.projection_wkt_record(WKT)])
        out = path('tile-out')
        result = run(las, '--output-dir', out, '--output-format', 'las, ply,vtp', *QUICK)
        pd = self.assertSucceeds(result, out, 'tile')
        self.assertIn('wrote the data (las):', result.stdout)
        self.assertIn('wrote the data (ply):', result.stdout)
        source, written = las_writer.read_las(las), las_writer.read_las(os.path.join(out, 'tile-gls.las'))
        kept = source['points'][~withheld]
        self.assertEqual(written['count'], len(kept))
        np.testing.assert_array_equal(written['scale'], source['scale'])
        np.testing.assert_array_equal(written['offset'], source['offset'])
        for field in ('X', 'Y', 'Z', 'intensity', 'returns', 'classification', 'scan_angle', 'gps_time'):
            np.testing.assert_array_equal(written['points'][field], kept[field], field)
        self.assertEqual(written['records'][('LASF_Projection', 2112)].rstrip(b'\0').decode(), WKT)
        feature = point_array(pd, 'GLSFeature')
        np.testing.assert_array_equal(written['extra']['GLSFeature'], feature.astype(np.float32))
        normals = point_array(pd, 'Normals')
        for c, axis in enumerate('xyz'):
            np.testing.assert_array_equal(written['extra']['Normals_' + axis], normals[:, c].astype(np.float32))
        # The PLY: x y z as the input's doubles, nx ny nz, and the GLS arrays.
        ply = read_ply(os.path.join(out, 'tile-gls.ply'))
        np.testing.assert_array_equal(np.column_stack([ply['x'], ply['y'], ply['z']]),
                                      vtk_to_numpy(pd.GetPoints().GetData()))
        np.testing.assert_array_equal(ply['nx'], normals[:, 0])
        np.testing.assert_array_equal(ply['scalar_GLSFeature'], feature)
        if shutil.which('CloudCompare'):
            fields = cloudcompare_scalar_fields(os.path.join(out, 'tile-gls.ply'), path('tile-cc.asc'))
            for name in ('GLSFeature', 'GLSStableKappa'):
                self.assertIn(name, fields)
        # A format the job does not write: one line, before any work.
        self.assertFailsInOneLine(run(las, '--output-dir', path('xyz-out'), '--output-format', 'vtp,xyz'),
                                  '--output-format takes a comma list of vtp, las, ply', path('xyz-out'))

    @staticmethod
    def camera(state, name):
        import re
        at = state.index('name="%s"' % name)
        return np.array([float(v) for v in re.findall(r'value="([^"]+)"', state[at:at + 400])[:3]])

    def test_a_terrestrial_room_scan_exported_as_las_faces_into_the_room(self):
        # No scan angles, one return, unclassified: not airborne, so nothing is forced up; the ground rule turns
        # the spanning tree so that the floor faces up, and the ceiling then faces down, into the room.
        points, truth = room()
        las = path('room.las')
        las_writer.write_las(las, points, point_format=1, scale=0.0005)
        out = path('room-out')
        result = run(las, '--output-dir', out, *QUICK)
        pd = self.assertSucceeds(result, out, 'room')
        self.assertIn('oriented automatic: minimum spanning tree, the ground or floor up: terrestrial lidar',
                      result.stdout)
        normals = point_array(pd, 'Normals').astype(float)
        defined = np.isfinite(normals).all(axis=1)
        agree = np.einsum('ij,ij->i', normals[defined], truth[defined]) > 0
        ceiling = truth[defined, 2] < -0.5
        print('room: %.3f%% into the room, the ceiling %.3f%% down' % (100 * agree.mean(), 100 * agree[ceiling].mean()))
        self.assertGreaterEqual(agree.mean(), 0.999)
        self.assertGreaterEqual(agree[ceiling].mean(), 0.999)
        # Asked for, the outward spanning tree turns it inside out (what the lidar rule avoids).
        out = path('room-mst-out')
        pd = self.assertSucceeds(run(las, '--output-dir', out, '--orientation', 'mst', *QUICK), out, 'room')
        normals = point_array(pd, 'Normals').astype(float)
        self.assertLess(np.mean(np.einsum('ij,ij->i', normals[defined], truth[defined]) > 0), 0.5)

    def test_a_pdal_pcd_with_upper_case_fields(self):
        rng = np.random.default_rng(7)
        points = rng.normal(size=(3000, 3))
        points /= np.linalg.norm(points, axis=1)[:, None]
        pcd = path('pdal.pcd')
        write_pcd(pcd, points, 3000, 1, fields='X Y Z Intensity', extra=np.arange(3000.0))
        out = path('pdal-out')
        pd = self.assertSucceeds(run(pcd, '--output-dir', out, '--orientation', 'mst', *QUICK), out, 'pdal')
        np.testing.assert_array_equal(point_array(pd, 'Intensity'), np.arange(3000.0, dtype=np.float32))
        kappa = point_array(pd, 'GLSStableKappa')
        self.assertLess(abs(np.nanmedian(kappa) - 1.0), 0.05)

    def assertFailsInOneLine(self, result, words, out):
        self.assertEqual(result.returncode, 2, failure_text(result))
        lines = error_lines(result)
        self.assertEqual(len(lines), 1, result.stderr)
        self.assertIn(words, lines[0])
        self.assertFalse(os.path.exists(out) and [f for f in os.listdir(out) if not f.startswith('.keep')])
        return lines[0]

    def test_what_a_file_is_by_its_content_and_other_messages(self):
        points, _, _, _, _, _ = aerial_strip()
        las = path('named.xyz')
        las_writer.write_las(las, points[:2000], point_format=1)
        self.assertFailsInOneLine(run(las, '--output-dir', path('named-out')),
                                  'a LAS file by its content (named .xyz), not a text point cloud: open it as .las',
                                  path('named-out'))
        noise = path('noise.pcd')
        with open(noise, 'wb') as f:
            f.write(np.random.default_rng(2).integers(0, 256, 5000, dtype=np.uint8).tobytes())
        self.assertFailsInOneLine(run(noise, '--output-dir', path('noise-out')),
                                  'a binary file by its content (named .pcd), not a PCD file', path('noise-out'))
        os.makedirs(path('a-folder'), exist_ok=True)
        self.assertFailsInOneLine(run(path('a-folder'), '--output-dir', path('folder-out')), 'a directory, not a file',
                                  path('folder-out'))
        # --query: refused before any stage (a LAS file announces its count: before it is read).
        real = path('query.las')
        las_writer.write_las(real, points[:2000], point_format=1)
        result = run(real, '--output-dir', path('query-out'), '--query', '2000')
        self.assertFailsInOneLine(result, '--query 2000 is not a point of the input (0 to 1999)', path('query-out'))
        self.assertNotIn('input:', result.stdout)
        frame, _, missing = depth_camera_scene(40, 30)
        pcd = path('gaps.pcd')
        write_pcd(pcd, frame, 40, 30)
        gap = int(np.flatnonzero(missing)[0])
        result = run(pcd, '--output-dir', path('gap-out'), '--query', str(gap))
        self.assertFailsInOneLine(result, '--query %d is a point with a non-finite coordinate' % gap, path('gap-out'))
        self.assertNotIn('normals:', result.stdout)
        # --orientation sensor on a file without one.
        self.assertFailsInOneLine(run(real, '--output-dir', path('sensor-out'), '--orientation', 'sensor'),
                                  '--orientation sensor: %s gives no scanner position' % real, path('sensor-out'))

    def test_a_full_disk_is_exit_2_with_the_writers_reason(self):
        # An output directory on a file system of 200 KiB (a tmpfs: mounting it needs root, as CI runs): the results
        # do not fit, and the job ends with one line and exit status 2, leaving nothing there.
        points, truth = room(spacing=0.15)
        las = path('small-room.las')
        las_writer.write_las(las, points, point_format=1)
        disk = path('full-disk')
        os.makedirs(disk, exist_ok=True)
        if subprocess.run(['mount', '-t', 'tmpfs', '-o', 'size=200k', 'tmpfs', disk], capture_output=True).returncode:
            self.skipTest('cannot mount a small file system here (not root)')
        try:
            out = os.path.join(disk, 'out')
            result = run(las, '--output-dir', out, *QUICK)
            line = self.assertFailsInOneLine(result, 'cannot write', out)
            self.assertIn('No space left on device', line)
            self.assertEqual(os.listdir(out), [])  # neither results nor the staging folder
        finally:
            subprocess.run(['umount', disk])

    def test_a_killed_jobs_staging_folder_goes_and_sigterm_waits_for_the_job(self):
        out = path('killed-out')
        os.makedirs(out, exist_ok=True)
        # What a SIGKILLed job left (its process gone), and the folder of a job that still runs (this process).
        stale = os.path.join(out, gls_outputs.STAGING_PREFIX + '999999999-x1')
        running = os.path.join(out, gls_outputs.STAGING_PREFIX + '%d-x2' % os.getpid())
        for folder in (stale, running):
            os.makedirs(folder, exist_ok=True)
            open(os.path.join(folder, 'partial.vtp'), 'w').close()
        points, _ = room()
        las = path('sigterm.las')
        las_writer.write_las(las, points, point_format=1)
        env = dict(os.environ)
        env.pop('DISPLAY', None)
        job = subprocess.Popen([ANALYZE, las, '--output-dir', out], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True, env=env)
        for line in job.stdout:
            if line.startswith('normals:'):
                break
        started = time.time()
        job.send_signal(signal.SIGTERM)
        stdout, stderr = job.communicate(timeout=120)
        print('SIGTERM: the job stopped %.1f s after the signal' % (time.time() - started))
        self.assertEqual(job.returncode, 130, stderr[-2000:])
        self.assertIn('interrupted; no results written', stderr)
        # When the process the user started has returned, nothing of the job runs or remains.
        self.assertFalse([pid for pid in os.listdir('/proc') if pid.isdigit() and out in self.cmdline(pid)])
        self.assertEqual(sorted(os.listdir(out)), [os.path.basename(running)])

    @staticmethod
    def cmdline(pid):
        try:
            with open('/proc/%s/cmdline' % pid, 'rb') as f:
                return f.read().replace(b'\0', b' ').decode(errors='replace')
        except OSError:
            return ''

    def test_a_long_title_is_wrapped_to_the_picture(self):
        title = 'GLS continuous features: ' + 'a-very-long-survey-tile-name_' * 6 + ' (100000000 points)'
        lines = gls_render.wrapped_title(title, 22, 1200).split('\n')
        self.assertGreater(len(lines), 1)
        self.assertTrue(all(len(line) * gls_render.TITLE_CHARACTER_WIDTH * 22 <= 1200 for line in lines), lines)
        self.assertEqual(''.join(lines).replace(' ', ''), title.replace(' ', ''))
        self.assertEqual(gls_render.wrapped_title('short', 22, 1200), 'short')


if __name__ == '__main__':
    os.makedirs(WORK, exist_ok=True)
    unittest.main(argv=sys.argv[:1] + sys.argv[3:], verbosity=2)
