"""pvpython tests of the GrowingLeastSquares plugin and of the Python-wrapped VTK classes.

Run by CTest as: pvpython test_plugin.py <plugin.so> <bunny.obj>, with PYTHONPATH holding the glsvtk package.
Every proxy runs on analytic shapes (asserted against the analytic values) and on the bundled scan (asserted equal,
bit for bit, to the wrapped C++ filter run directly with the same parameters)."""
import math
import os
import sys
import tempfile
import unittest

import numpy as np
from paraview import simple
from paraview import servermanager
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkIOGeometry import vtkOBJReader
from vtkmodules.vtkIOImage import vtkPNGReader

import glsvtk
from shapes import sphere

PLUGIN, BUNNY = sys.argv[1], sys.argv[2]
NS = {}


def polydata(points, normals=None):
    pd = vtkPolyData()
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(points, dtype=np.float64), deep=True))
    pd.SetPoints(pts)
    n = len(points)
    cells = vtkCellArray()
    cells.SetData(numpy_to_vtkIdTypeArray(np.arange(n + 1, dtype=np.int64), deep=True),
                  numpy_to_vtkIdTypeArray(np.arange(n, dtype=np.int64), deep=True))
    pd.SetVerts(cells)
    if normals is not None:
        a = numpy_to_vtk(np.ascontiguousarray(normals, dtype=np.float64), deep=True)
        a.SetName('Normals')
        pd.GetPointData().SetNormals(a)
    return pd


def flower_curve(n, amplitude=0.25):
    """The closed polyline r = 1 + amplitude cos(5 theta), counter-clockwise, without normals."""
    theta = 2 * math.pi * np.arange(n) / n
    r = 1 + amplitude * np.cos(5 * theta)
    pd = polydata(np.stack([r * np.cos(theta), r * np.sin(theta), 0 * theta], axis=1))
    lines = vtkCellArray()
    lines.InsertNextCell(n + 1)
    for i in list(range(n)) + [0]:
        lines.InsertCellPoint(i)
    pd.SetVerts(vtkCellArray())
    pd.SetLines(lines)
    return pd


def producer(pd):
    source = simple.TrivialProducer()
    source.GetClientSideObject().SetOutput(pd)
    return source


def fetch(proxy):
    proxy.UpdatePipeline()
    return servermanager.Fetch(proxy)


def array(pd, name):
    a = pd.GetPointData().GetArray(name)
    assert a is not None, 'missing array %s' % name
    return vtk_to_numpy(a)


def run_vtk(filter_object, pd):
    filter_object.SetInputData(pd)
    filter_object.Update()
    return filter_object.GetOutput()


def bunny_points():
    reader = vtkOBJReader()
    reader.SetFileName(BUNNY)
    reader.Update()
    return polydata(vtk_to_numpy(reader.GetOutput().GetPoints().GetData()))


class PluginProxies(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        simple.LoadPlugin(PLUGIN, remote=False, ns=globals())  # a fresh dict passed as ns stays empty
        for name in ('GLSNormalEstimation', 'GLSScaleSpace', 'GLSGeometricVariation', 'GLSContinuousFeatures',
                     'GLSMultiScaleDissimilarity', 'GLSScaleProfiles', 'GLSScaleSpaceImage', 'GLSPointCloudReader',
                     'GLSAdaptiveBandwidth', 'GLSProjection', 'GLSPrincipalDirections'):
            NS[name] = globals()[name]
        cls.points, cls.normals = sphere(3000, 2.0)

    def test_every_proxy_is_registered_with_its_properties(self):
        s = NS['GLSScaleSpace']()
        for prop in ('MinScale', 'MaxScale', 'NumberOfScales', 'ScaleSampling', 'Scales', 'ScaleUnits', 'Normals'):
            self.assertIn(prop, s.ListProperties())
        self.assertEqual(s.ScaleUnits, 'Relative to bounding box diagonal')
        self.assertEqual(s.ScaleSampling, 'Quadratic')
        d = NS['GLSMultiScaleDissimilarity']()
        for prop in ('QueryPointId', 'PriorMinScale', 'PriorMaxScale', 'PriorShape', 'Threshold', 'QueryPoint'):
            self.assertIn(prop, d.ListProperties())
        n = NS['GLSNormalEstimation']()
        for prop in ('NeighborhoodType', 'NumberOfNeighbors', 'Radius', 'Orientation', 'OrientationPoint'):
            self.assertIn(prop, n.ListProperties())
        for p in (s, d, n):
            simple.Delete(p)

    def test_text_clouds_open_with_the_point_cloud_reader(self):
        # File > Open and pvpython's OpenDataFile: .xyz, .pts, .ptx and .pcd are the GLS Point Cloud Reader's; a .csv
        # or .txt point cloud opens with the same reader (proxy CSVPointCloudReader), offered before ParaView's CSV
        # and GDAL readers (the GUI's "choose a reader" dialog lists them in this order, the first selected); a .csv
        # table that is no point cloud still opens with the CSV reader, as a table.
        folder = tempfile.mkdtemp()
        factory = servermanager.vtkSMProxyManager.GetProxyManager().GetReaderFactory()
        session = servermanager.ActiveConnection.Session
        ours = {'xyz': 'GLSPointCloudReader', 'pts': 'GLSPointCloudReader',
                'csv': 'CSVPointCloudReader', 'txt': 'CSVPointCloudReader'}
        for extension, separator in (('xyz', ' '), ('pts', ' '), ('csv', ','), ('txt', ' ')):
            path = os.path.join(folder, 'cloud.' + extension)
            with open(path, 'w') as f:
                f.write(''.join(separator.join(str(v) for v in row) + '\n' for row in
                                ((0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0.5))))
            readers = factory.GetReaders(path, session)
            names = [readers.GetString(i) for i in range(1, readers.GetLength(), 3)]
            self.assertEqual(names[0], ours[extension], (extension, names))
            if extension in ('csv', 'txt'):
                self.assertIn('CSVReader', names)
            opened = simple.OpenDataFile(path)
            self.assertEqual(opened.GetXMLName(), ours[extension], extension)
            opened.UpdatePipeline()
            cloud = servermanager.Fetch(opened)
            self.assertEqual(cloud.GetClassName(), 'vtkPolyData', extension)
            self.assertEqual(cloud.GetNumberOfPoints(), 4, extension)
            self.assertAlmostEqual(cloud.GetPoint(3)[2], 0.5)
            simple.Delete(opened)
            reader = NS['GLSPointCloudReader'](FileName=path)
            reader.UpdatePipeline()
            self.assertEqual(servermanager.Fetch(reader).GetNumberOfPoints(), 4, extension)
            simple.Delete(reader)
        table = os.path.join(folder, 'table.csv')
        with open(table, 'w') as f:
            f.write('time,value\n0,1.5\n1,2.5\n')
        readers = factory.GetReaders(table, session)
        self.assertNotIn('CSVPointCloudReader', [readers.GetString(i) for i in range(1, readers.GetLength(), 3)])
        opened = simple.OpenDataFile(table)
        self.assertEqual(opened.GetXMLName(), 'CSVReader')
        opened.UpdatePipeline()
        self.assertEqual(opened.GetDataInformation().GetDataSetTypeAsString(), 'vtkTable')
        simple.Delete(opened)

    def test_las_files_open_with_the_las_reader_without_gdals_failed_probe(self):
        # ParaView asks every reader whether it reads a .las file, GDAL's among them, whose failed probe printed
        # "ERROR 4: ... not recognized as a supported file format" on every open; the plugin drops that message for
        # .las and .laz files only (another file's still shows). In a pvpython of its own, whose output is read.
        import subprocess
        import las_writer
        folder = tempfile.mkdtemp()
        las, other = os.path.join(folder, 'tile.las'), os.path.join(folder, 'image.tif')
        las_writer.write_las(las, sphere(200)[0], point_format=1)
        with open(other, 'w') as f:
            f.write('not an image')
        script = ('from paraview.simple import *\n'
                  'LoadPlugin(%r, remote=False, ns=globals())\n'
                  'r = OpenDataFile(%r)\nprint(r.GetXMLName())\nr.UpdatePipeline()\n'
                  'print(r.GetDataInformation().GetNumberOfPoints())\n'
                  'from vtkmodules.vtkIOGDAL import vtkGDALRasterReader\n'
                  'g = vtkGDALRasterReader()\ng.SetFileName(%r)\ng.UpdateInformation()\n' % (PLUGIN, las, other))
        result = subprocess.run(['pvpython', '-c', script], capture_output=True, text=True, timeout=120)
        self.assertEqual(result.stdout.split()[:2], ['GLSLasReader', '200'], result.stderr[-2000:])
        self.assertNotIn("tile.las' not recognized", result.stderr)
        self.assertIn("image.tif' not recognized", result.stderr)  # GDAL's other messages pass

    def test_results_saved_as_las_and_ply_with_every_gls_array(self):
        # File > Save Data (pvpython SaveData) as .las and .ply takes the GLS writers: the LAS read back by the GLS LAS
        # Reader (OpenDataFile) with GLSFeature and the Normals as float32, the PLY parsed here with the
        # scalar_GLSFeature property CloudCompare loads as a scalar field.
        from main_job_helpers import read_ply
        folder = tempfile.mkdtemp()
        features = NS['GLSContinuousFeatures'](Input=producer(polydata(self.points, self.normals)))
        computed = fetch(features)
        feature = array(computed, 'GLSFeature')
        las, ply = os.path.join(folder, 'sphere.las'), os.path.join(folder, 'sphere.ply')
        simple.SaveData(las, proxy=features)
        simple.SaveData(ply, proxy=features)
        opened = simple.OpenDataFile(las)
        self.assertEqual(opened.GetXMLName(), 'GLSLasReader')
        back = fetch(opened)
        np.testing.assert_array_equal(array(back, 'GLSFeature'), feature.astype(np.float32))
        np.testing.assert_array_equal(array(back, 'Normals'), self.normals.astype(np.float32))
        # A point set from no LAS file: the finest power of ten whose 32-bit integers hold the 4 m extent, 1e-8; each
        # position within half of it.
        scale = vtk_to_numpy(back.GetFieldData().GetArray('LasScale'))[0]
        np.testing.assert_array_equal(scale, [1e-8, 1e-8, 1e-8])
        np.testing.assert_allclose(vtk_to_numpy(back.GetPoints().GetData()), self.points, rtol=0, atol=0.5e-8 * 1.001)
        vertices = read_ply(ply)
        np.testing.assert_array_equal(vertices['scalar_GLSFeature'], feature)
        np.testing.assert_array_equal(vertices['nx'], self.normals[:, 0].astype(np.float32))
        simple.Delete(opened)
        simple.Delete(features)

    def test_an_unstructured_grid_and_a_multiblock_are_in_every_filters_input_domain(self):
        # The GUI greys out a filter whose input domain refuses the selected source (once vtkPolyData only).
        grid = simple.AppendDatasets(Input=simple.Sphere())  # a vtkUnstructuredGrid
        group = simple.GroupDatasets(Input=[simple.Sphere(), simple.Sphere(Center=[2, 0, 0])])
        for source, kind in ((grid, 'vtkUnstructuredGrid'), (group, 'vtkMultiBlockDataSet')):
            source.UpdatePipeline()
            self.assertEqual(source.GetDataInformation().GetDataSetTypeAsString(), kind)
            for name in ('GLSNormalEstimation', 'GLSScaleSpace', 'GLSGeometricVariation', 'GLSContinuousFeatures',
                         'GLSMultiScaleDissimilarity', 'GLSAdaptiveBandwidth', 'GLSProjection'):
                f = NS[name](Input=source)
                domain = f.SMProxy.GetProperty('Input').FindDomain('vtkSMDataTypeDomain')
                self.assertTrue(domain.IsInDomain(source.SMProxy, 0), (name, kind))
                simple.Delete(f)
        normals = NS['GLSNormalEstimation'](Input=grid)
        normals.UpdatePipeline()
        self.assertEqual(normals.GetDataInformation().GetDataSetTypeAsString(), 'vtkUnstructuredGrid')
        simple.Delete(normals)

    def test_scale_space_on_a_sphere(self):
        src = producer(polydata(self.points, self.normals))
        s = NS['GLSScaleSpace'](Input=src, ScaleUnits='Absolute', MinScale=0.4, MaxScale=2.0, NumberOfScales=5,
                                ScaleSampling='Logarithmic')
        out = fetch(s)
        scales = vtk_to_numpy(out.GetFieldData().GetArray('GLSScales'))
        np.testing.assert_allclose(scales, 0.4 * 5.0 ** (np.arange(5) / 4.0), rtol=1e-14)
        np.testing.assert_allclose(array(out, 'GLSKappa'), 0.5, atol=1e-9)
        np.testing.assert_allclose(array(out, 'GLSTau'), 0.0, atol=1e-10)
        np.testing.assert_allclose(array(out, 'GLSFitness'), 1.0, atol=1e-9)
        self.assertEqual(array(out, 'GLSEta').shape, (3000, 15))
        s.Scales = [0.5, 1.0]
        out = fetch(s)
        np.testing.assert_array_equal(vtk_to_numpy(out.GetFieldData().GetArray('GLSScales')), [0.5, 1.0])
        simple.Delete(s)
        simple.Delete(src)

    def test_variation_features_dissimilarity_on_a_sphere(self):
        src = producer(polydata(self.points, self.normals))
        v = NS['GLSGeometricVariation'](Input=src, NumberOfScales=6, MinScale=0.05, MaxScale=0.3)
        f = NS['GLSContinuousFeatures'](Input=v, FeatureMeasure='Log scale')
        d = NS['GLSMultiScaleDissimilarity'](Input=f, QueryPointId=10, PriorShape='LogGaussian')
        out = fetch(d)
        np.testing.assert_allclose(array(out, 'GLSGeometricVariation'), 0.0, atol=1e-12)
        np.testing.assert_allclose(array(out, 'GLSFeature'), 0.0, atol=1e-12)
        np.testing.assert_allclose(array(out, 'GLSDissimilarity'), 0.0, atol=1e-18)
        self.assertTrue(np.all(array(out, 'GLSSimilar') == 1))
        self.assertTrue(np.all(array(out, 'GLSPertinentScaleCount') == 0))
        for p in (d, f, v, src):
            simple.Delete(p)

    def test_principal_directions_at_a_chosen_scale_show_as_glyphs(self):
        # A cylinder of radius 1 (outward normals): at the chosen scale k1 = 1 and d1 goes around it, so ParaView's
        # Glyph (lines, oriented by the active vectors the filter sets) draws every line across the axis.
        u, z = np.meshgrid(np.arange(-0.3, 0.3, 0.008), np.arange(-0.3, 0.3, 0.008))
        u, z = u.ravel(), z.ravel()
        normals = np.stack([np.cos(u), np.sin(u), 0 * u], axis=1)
        src = producer(polydata(normals + np.stack([0 * u, 0 * u, z], axis=1), normals))
        d = NS['GLSPrincipalDirections'](Input=src, ScaleUnits='Absolute', MinScale=0.05, MaxScale=0.1,
                                         NumberOfScales=4, DirectionScale=0.07)
        out = fetch(d)
        scales = vtk_to_numpy(out.GetFieldData().GetArray('GLSScales'))
        chosen = out.GetFieldData().GetArray('GLSDirectionScale').GetValue(0)
        self.assertEqual(chosen, scales[np.argmin(np.abs(np.log(scales / 0.07)))])
        self.assertEqual(out.GetPointData().GetVectors().GetName(), 'GLSPrincipalDirection1AtScale')
        inside = (np.abs(u) < 0.2) & (np.abs(z) < 0.2)
        np.testing.assert_allclose(array(out, 'GLSK1AtScale')[inside], 1.0, atol=0.03)
        np.testing.assert_allclose(array(out, 'GLSK2AtScale')[inside], 0.0, atol=0.03)
        glyphs = simple.Glyph(Input=d, GlyphType='Line', OrientationArray=['POINTS', 'GLSPrincipalDirection1AtScale'],
                              ScaleArray=['POINTS', 'No scale array'], ScaleFactor=0.01, GlyphMode='All Points')
        lines = fetch(glyphs)
        per_glyph = lines.GetNumberOfPoints() // len(u)  # the line source's points, one line a point
        self.assertEqual(lines.GetNumberOfPoints(), per_glyph * len(u))
        self.assertGreaterEqual(per_glyph, 2)
        ends = vtk_to_numpy(lines.GetPoints().GetData()).reshape(-1, per_glyph, 3)
        centres, along = ends.mean(axis=1), ends[:, -1] - ends[:, 0]
        along /= np.linalg.norm(along, axis=1)[:, None]
        centre_u = np.arctan2(centres[:, 1], centres[:, 0])
        within = (np.abs(centre_u) < 0.2) & (np.abs(centres[:, 2]) < 0.2)
        self.assertGreater(within.sum(), 1000)
        self.assertLess(np.abs(along[within, 2]).max(), math.sin(math.radians(2)))  # across the axis
        radial = np.stack([np.cos(centre_u), np.sin(centre_u), 0 * centre_u], axis=1)[within]
        self.assertLess(np.abs((along[within] * radial).sum(axis=1)).max(), math.sin(math.radians(2)))  # tangent
        for p in (glyphs, d, src):
            simple.Delete(p)

    def test_normals_on_a_sphere_point_outward(self):
        src = producer(polydata(self.points))
        n = NS['GLSNormalEstimation'](Input=src, Orientation='Minimum spanning tree')
        out = fetch(n)
        dots = np.einsum('ij,ij->i', vtk_to_numpy(out.GetPointData().GetNormals()), self.normals)
        self.assertGreater(dots.min(), 0.999)
        n.Orientation = 'Towards point'
        n.OrientationPoint = [0, 0, 0]
        dots = np.einsum('ij,ij->i', vtk_to_numpy(fetch(n).GetPointData().GetNormals()), self.normals)
        self.assertLess(dots.max(), -0.999)
        simple.Delete(n)
        simple.Delete(src)

    def test_bunny_pipeline_equals_the_wrapped_cpp_filters(self):
        cloud = bunny_points()
        src = producer(cloud)
        n = NS['GLSNormalEstimation'](Input=src, NumberOfNeighbors=12)
        s = NS['GLSScaleSpace'](Input=n, NumberOfScales=8, ScaleSampling='Linear', MinScale=0.01, MaxScale=0.05)
        v = NS['GLSGeometricVariation'](Input=s, WTau=2.0)
        f = NS['GLSContinuousFeatures'](Input=v, SigmaMode='Absolute', Sigma=0.2)
        d = NS['GLSMultiScaleDissimilarity'](Input=f, QueryPointId=777, PriorMinScale=0.02, PriorMaxScale=0.04,
                                             Threshold=0.02)
        proxy_out = fetch(d)

        normals = glsvtk.vtkGLSNormalEstimation()
        normals.SetNumberOfNeighbors(12)
        scale_space = glsvtk.vtkGLSScaleSpace()
        scale_space.SetNumberOfScales(8)
        scale_space.SetScaleSamplingToLinear()
        scale_space.SetMinScale(0.01)
        scale_space.SetMaxScale(0.05)
        variation = glsvtk.vtkGLSGeometricVariation()
        variation.SetWTau(2.0)
        features = glsvtk.vtkGLSContinuousFeatures()
        features.SetSigmaModeToAbsolute()
        features.SetSigma(0.2)
        dissimilarity = glsvtk.vtkGLSMultiScaleDissimilarity()
        dissimilarity.SetQueryPointId(777)
        dissimilarity.SetPriorMinScale(0.02)
        dissimilarity.SetPriorMaxScale(0.04)
        dissimilarity.SetThreshold(0.02)
        data = cloud
        for algorithm in (normals, scale_space, variation, features, dissimilarity):
            data = run_vtk(algorithm, data)
        self.assertEqual(data.GetNumberOfPoints(), 35947)
        names = ('Normals', 'GLSTau', 'GLSEta', 'GLSKappa', 'GLSFitness', 'GLSdTau', 'GLSdEta', 'GLSdKappa',
                 'GLSNeighborCount', 'GLSGeometricVariation', 'GLSPertinentScales', 'GLSPertinentScaleCount',
                 'GLSFeature', 'GLSDissimilarity', 'GLSSimilar')
        for name in names:
            np.testing.assert_array_equal(array(proxy_out, name), array(data, name), err_msg=name)
        feature = array(data, 'GLSFeature')
        self.assertLess(np.nanmin(feature), 0.1)
        self.assertGreater(np.nanmax(feature), 0.9)
        self.assertEqual(array(data, 'GLSDissimilarity')[777], 0.0)
        for p in (d, f, v, s, n, src):
            simple.Delete(p)

    def test_scale_profiles_table_equals_the_wrapped_filter(self):
        src = producer(polydata(self.points, self.normals))
        p = NS['GLSScaleProfiles'](Input=src, PointIds=[5, 700], NumberOfScales=250, ScaleUnits='Absolute',
                                   MinScale=0.2, MaxScale=1.5)
        p.UpdatePipeline()
        table = servermanager.Fetch(p)
        self.assertEqual(table.GetNumberOfRows(), 250)
        direct = glsvtk.vtkGLSScaleProfiles()
        direct.AddPointId(5)
        direct.AddPointId(700)
        direct.SetNumberOfScales(250)
        direct.SetScaleUnitsToAbsolute()
        direct.SetMinScale(0.2)
        direct.SetMaxScale(1.5)
        direct.SetInputData(polydata(self.points, self.normals))
        direct.Update()
        reference = direct.GetOutputTable()
        for i in range(table.GetNumberOfColumns()):
            name = table.GetColumnName(i)
            np.testing.assert_array_equal(vtk_to_numpy(table.GetColumnByName(name)),
                                          vtk_to_numpy(reference.GetColumnByName(name)), err_msg=name)
        t = vtk_to_numpy(table.GetColumnByName('t'))
        np.testing.assert_allclose(vtk_to_numpy(table.GetColumnByName('t*kappa (700)')), t / 2.0, atol=1e-9)
        simple.Delete(p)
        simple.Delete(src)

    def test_scale_profiles_of_the_main_jobs_crop_equal_the_whole_clouds(self):
        # The main job computes its profiles on the picked points' neighbourhoods only (gls_profiles.around), at the
        # analysis' scales as lengths, exactly, with the minimum neighbour count the analysis applied (field data
        # GLSMinimumNeighbors): the same table as on the whole cloud, to rounding (the sums run in the order of the
        # grid's cells, laid on the crop's box, on coordinates from the crop's own low corner (vtkGLSCloud::Anchor):
        # 5e-15 relative seen, and 3.2e-15 absolute on tau/t, 1e-3 at most, where it crosses zero).
        import main_job_helpers  # noqa: F401 (it makes the main job's own modules importable)
        import gls_profiles
        normals = NS['GLSNormalEstimation'](Input=producer(bunny_points()))
        features = NS['GLSContinuousFeatures'](Input=normals, Normals=['POINTS', 'Normals'], NumberOfScales=5)
        whole = fetch(normals)
        fd = fetch(features).GetFieldData()
        scales = vtk_to_numpy(fd.GetArray('GLSScales'))
        minimum = int(fd.GetArray('GLSMinimumNeighbors').GetValue(0))
        self.assertEqual(minimum, 6)  # the automatic minimum of 3D data
        picks = [17, 9000, 30000]
        crop, ids = gls_profiles.around(whole, picks, scales[-1] * 1.001)
        self.assertLess(crop.GetNumberOfPoints(), whole.GetNumberOfPoints() // 2)
        tables = []
        for cloud, pids in ((whole, picks), (crop, ids)):
            src = producer(cloud)
            p = NS['GLSScaleProfiles'](Input=src, Normals=['POINTS', 'Normals'], PointIds=pids, NumberOfScales=60,
                                       ScaleUnits='Absolute', MinScale=scales[0], MaxScale=scales[-1],
                                       Evaluation='Exact', MinimumNeighbors=minimum)
            tables.append(fetch(p))
            simple.Delete(p)
            simple.Delete(src)
        self.assertEqual(tables[0].GetNumberOfColumns(), tables[1].GetNumberOfColumns())
        for i in range(tables[0].GetNumberOfColumns()):
            name = tables[0].GetColumnName(i)
            renamed = name
            for pid, cid in zip(picks, ids):
                renamed = renamed.replace('(%d)' % pid, '(%d)' % cid)
            self.assertTrue(name == 't' or renamed != name, name)
            np.testing.assert_allclose(vtk_to_numpy(tables[1].GetColumnByName(renamed)),
                                       vtk_to_numpy(tables[0].GetColumn(i)), rtol=1e-12, atol=1e-14, err_msg=name)
        simple.Delete(features)
        simple.Delete(normals)

    def test_denoising_pipeline_on_a_noisy_sphere(self):
        # Noise on the radius of one hemisphere (z > 0); the other stays clean.
        rng = np.random.default_rng(4)
        radial = np.where(self.points[:, 2] > 0, 1.0 + rng.normal(0.0, 0.01, len(self.points)), 1.0)
        noisy = self.points * radial[:, None]
        src = producer(polydata(noisy, self.normals))
        bandwidth = NS['GLSAdaptiveBandwidth'](Input=src, ScaleUnits='Absolute', MinScale=0.15, MaxScale=1.5,
                                               NumberOfScales=30, ScaleSampling='Logarithmic',
                                               SmoothingRadius=0.3, Threshold=0.01)
        projection = NS['GLSProjection'](Input=bandwidth)
        self.assertEqual(projection.ScaleMode, 'Automatic')
        out = fetch(projection)
        moved = vtk_to_numpy(out.GetPoints().GetData())
        radius = np.linalg.norm(moved, axis=1)
        top = self.points[:, 2] > 0.2
        before = np.sqrt(np.mean((2.0 * radial[top] - 2.0) ** 2))
        after = np.sqrt(np.mean((radius[top] - 2.0) ** 2))
        self.assertLess(after * 2.5, before)
        bw = array(fetch(bandwidth), 'GLSBandwidth')
        self.assertGreater(np.median(bw[top]), 1.5 * np.median(bw[self.points[:, 2] < -0.5]))
        normals = array(out, 'Normals').reshape(-1, 3)
        np.testing.assert_allclose(np.sum(normals * moved, axis=1) / radius, 1.0, atol=5e-3)
        # The same through the wrapped C++ filters, bit for bit.
        direct_bw = glsvtk.vtkGLSAdaptiveBandwidth()
        direct_bw.SetScaleUnitsToAbsolute()
        direct_bw.SetMinScale(0.15)
        direct_bw.SetMaxScale(1.5)
        direct_bw.SetNumberOfScales(30)
        direct_bw.SetScaleSamplingToLogarithmic()
        direct_bw.SetSmoothingRadius(0.3)
        direct_bw.SetInputData(polydata(noisy, self.normals))
        direct = glsvtk.vtkGLSProjection()
        direct.SetInputConnection(direct_bw.GetOutputPort())
        direct.Update()
        np.testing.assert_array_equal(vtk_to_numpy(direct.GetOutput().GetPoints().GetData()), moved)
        fixed = NS['GLSProjection'](Input=src, ScaleMode='Fixed scale', ScaleUnits='Absolute', Scale=0.5)
        self.assertLess(np.sqrt(np.mean((np.linalg.norm(vtk_to_numpy(fetch(fixed).GetPoints().GetData()),
                                                        axis=1)[top] - 2.0) ** 2)) * 2.0, before)
        for p in (fixed, projection, bandwidth, src):
            simple.Delete(p)

    def test_scale_space_image_of_a_flower(self):
        # r = 1 + 0.25 cos(5 theta) has 10 inflections (the C++ test checks it analytically): 10 zero crossings of
        # kappa at the smallest scale, none left at t = 1, where kappa > 0 everywhere.
        src = producer(flower_curve(1000))
        p = NS['GLSScaleSpaceImage'](Input=src, ScaleUnits='Absolute', MinScale=0.02, MaxScale=1.0,
                                     NumberOfScales=50, NumberOfArclengthSamples=0)  # one column per point
        for prop in ('Closed', 'NumberOfArclengthSamples', 'WKappa', 'Normals'):
            self.assertIn(prop, p.ListProperties())
        p.UpdatePipeline()
        image = servermanager.Fetch(p, idx=0)
        crossings = servermanager.Fetch(p, idx=1)
        self.assertEqual(image.GetDimensions(), (1001, 50, 1))
        self.assertAlmostEqual(image.GetOrigin()[1], 0.02)
        self.assertAlmostEqual(image.GetSpacing()[1], 0.02)
        kappa = array(image, 'GLSKappa').reshape(50, 1001)
        scaled = array(image, 'GLSScaledKappa').reshape(50, 1001)
        np.testing.assert_allclose(scaled, kappa * (0.02 + 0.02 * np.arange(50))[:, None], rtol=1e-14)
        self.assertEqual(array(image, 'GLSNu').shape, (50 * 1001,))
        row = kappa[0, :-1]
        self.assertEqual(int(np.sum(np.sign(row) != np.sign(np.roll(row, 1)))), 10)
        self.assertTrue(np.all(kappa[-1] > 0))
        self.assertGreater(crossings.GetNumberOfLines(), 0)
        ys = vtk_to_numpy(crossings.GetPoints().GetData())[:, 1]
        self.assertEqual(int(np.sum(np.abs(ys - 0.02) < 1e-7)), 10)
        self.assertLess(ys.max(), 1.0)
        # The proxy runs the wrapped C++ filter: same numbers.
        direct = glsvtk.vtkGLSScaleSpaceImage()
        direct.SetScaleUnitsToAbsolute()
        direct.SetMinScale(0.02)
        direct.SetMaxScale(1.0)
        direct.SetNumberOfScales(50)
        direct.SetNumberOfArclengthSamples(0)
        direct.SetInputData(flower_curve(1000))
        direct.Update()
        np.testing.assert_array_equal(array(direct.GetImageOutput(), 'GLSKappa'), array(image, 'GLSKappa'))
        self.assertEqual(direct.GetCrossingsOutput().GetNumberOfLines(), crossings.GetNumberOfLines())
        simple.Delete(p)
        simple.Delete(src)

    def test_scale_space_image_shows_in_a_render_view_with_the_proxy_defaults(self):
        # The proxy's defaults: 200 scales for the image and the profiles (their base proxy's 20 stays for the
        # others), 1000 arclength columns, so that the image's extent is announced before it is computed: a
        # render view asks for it first and would otherwise get an empty image.
        src = producer(flower_curve(400))
        p = NS['GLSScaleSpaceImage'](Input=src)
        p.ScaleUnits = 'Absolute'  # an image about as tall as wide (arclength 7.3, t up to 3), easy to see
        p.MinScale = 0.05
        p.MaxScale = 3.0
        self.assertEqual(p.NumberOfScales, 200)
        self.assertEqual(p.NumberOfArclengthSamples, 1000)
        for name, scales in (('GLSScaleProfiles', 200), ('GLSScaleSpace', 20), ('GLSGeometricVariation', 20)):
            other = NS[name]()
            self.assertEqual(other.NumberOfScales, scales, name)
            simple.Delete(other)
        view = simple.CreateRenderView()
        view.ViewSize = [400, 300]
        view.OrientationAxesVisibility = 0
        for representation in ('Slice', 'Surface'):
            display = simple.Show(p, view)
            display.SetRepresentationType(representation)
            simple.ColorBy(display, ('POINTS', 'GLSScaledKappa'))
            view.ResetCamera()
            simple.Render(view)
            info = display.GetRepresentedDataInformation()
            self.assertEqual(info.GetNumberOfPoints(), 1000 * 200, representation)
            png = os.path.join(tempfile.mkdtemp(), 'image.png')
            simple.SaveScreenshot(png, view, ImageResolution=[400, 300])
            reader = vtkPNGReader()
            reader.SetFileName(png)
            reader.Update()
            pixels = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3]
            covered = np.mean(np.any(pixels != pixels[0], axis=1))
            self.assertGreater(covered, 0.2, representation)
            simple.Hide(p, view)
        simple.Delete(view)
        simple.Delete(p)
        simple.Delete(src)

    def test_errors_are_reported_not_fatal(self):
        src = producer(polydata(self.points))  # no normals
        s = NS['GLSScaleSpace'](Input=src)
        out = fetch(s)
        self.assertIsNone(out.GetPointData().GetArray('GLSKappa'))
        simple.Delete(s)
        simple.Delete(src)


class WrappedClasses(unittest.TestCase):
    def test_wrapped_scale_space_on_a_sphere(self):
        points, normals = sphere(2000, 0.5)
        s = glsvtk.vtkGLSScaleSpace()
        s.SetScaleUnitsToAbsolute()
        s.AddScale(0.1)
        s.AddScale(0.3)
        out = run_vtk(s, polydata(points, normals))
        np.testing.assert_allclose(array(out, 'GLSKappa'), 2.0, atol=1e-9)
        self.assertEqual(out.GetPointData().GetArray('GLSKappa').GetComponentName(1), 't=0.3')

    def test_wrapped_enumerations_and_errors(self):
        s = glsvtk.vtkGLSScaleSpace()
        s.SetScaleSamplingToLogarithmic()
        self.assertEqual(s.GetScaleSampling(), glsvtk.vtkGLSScaleSpace.LOGARITHMIC)
        s.SetMinScale(-1)
        s.GlobalWarningDisplayOff()
        points, normals = sphere(200, 1.0)
        out = run_vtk(s, polydata(points, normals))
        self.assertIsNone(out.GetPointData().GetArray('GLSKappa'))


if __name__ == '__main__':
    unittest.main(argv=[sys.argv[0]], verbosity=2)
