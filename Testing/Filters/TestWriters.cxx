// The GLS LAS and PLY writers: what they write read back by the GLS LAS Reader and by VTK's own PLY reader (an
// independent one): the positions as the input had them (a LAS input's integers), its attributes and coordinate
// system, every GLS array under its name (a vector as one), the faces; a missing return left out.
#include "FilterTestUtilities.h"

#include "vtkGLSLasReader.h"
#include "vtkGLSLasWriter.h"
#include "vtkGLSPlyWriter.h"

#include "vtkFloatArray.h"
#include "vtkPLYReader.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace glstest;

namespace
{

std::string outputFile(const std::string& name)
{
  return std::string(GLS_TEST_OUTPUT_DIR) + "/" + name;
}

/// A survey tile as the GLS LAS Reader gives one: positions on a millimetre grid at UTM coordinates, LAS attributes,
/// the file's scale, offset and coordinate system; with a GLS array and a vector (Normals) as the filters add them,
/// and one missing return (NaN) at point 7.
vtkSmartPointer<vtkPolyData> surveyTile(std::size_t n)
{
  std::vector<double> xyz, normals;
  for (std::size_t i = 0; i < n; ++i)
  {
    // integer * scale + offset, as a LAS reader computes a position
    xyz.insert(xyz.end(), { static_cast<double>(37 * i % 5000) * 0.001 + 652000.0,
      static_cast<double>(53 * i % 7000) * 0.001 + 5410000.0, static_cast<double>(100000 + i % 300) * 0.001 + 0.0 });
    normals.insert(normals.end(), { 0.0, 0.6, 0.8 });
  }
  xyz[21] = xyz[22] = xyz[23] = std::nan("");
  auto pd = makePolyData(xyz, normals);
  const auto add = [&](vtkDataArray* a, const char* name, int components) {
    a->SetName(name);
    a->SetNumberOfComponents(components);
    a->SetNumberOfTuples(static_cast<vtkIdType>(n));
    for (vtkIdType i = 0; i < static_cast<vtkIdType>(n); ++i)
    {
      for (int c = 0; c < components; ++c)
      {
        a->SetComponent(i, c, static_cast<double>((i * (c + 3)) % 250));
      }
    }
    pd->GetPointData()->AddArray(a);
  };
  add(vtkNew<vtkUnsignedShortArray>(), "Intensity", 1);
  add(vtkNew<vtkUnsignedCharArray>(), "Classification", 1);
  add(vtkNew<vtkUnsignedShortArray>(), "RGB", 3);
  add(vtkNew<vtkFloatArray>(), "GLSFeature", 1);
  const double scale[3] = { 0.001, 0.001, 0.001 }, offset[3] = { 652000.0, 5410000.0, 0.0 };
  for (const auto& field : { std::make_pair("LasScale", scale), std::make_pair("LasOffset", offset) })
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(field.first);
    a->SetNumberOfComponents(3);
    a->InsertNextTuple(field.second);
    pd->GetFieldData()->AddArray(a);
  }
  vtkNew<vtkStringArray> wkt;
  wkt->SetName("CoordinateSystemWKT");
  wkt->InsertNextValue("PROJCS[\"WGS 84 / UTM zone 32N\"]");
  pd->GetFieldData()->AddArray(wkt);
  return pd;
}

} // namespace

TEST(Writers, ALasFileWrittenIsReadBackWithTheInputsIntegersAttributesAndArrays)
{
  const std::size_t n = 400;
  auto tile = surveyTile(n);
  const std::string file = outputFile("writers-tile.las");
  vtkNew<vtkGLSLasWriter> writer;
  auto warnings = catchWarnings(writer);
  writer->SetFileName(file.c_str());
  writer->SetInputData(tile);
  ASSERT_EQ(writer->Write(), 1);
  EXPECT_NE(std::string(writer->GetDescription()).find("point format 7, 399 points (1 with a non-finite coordinate "
                                                       "left out), 4 Extra Bytes fields; scale 0.001 0.001 0.001, "
                                                       "the input's own"), std::string::npos)
    << writer->GetDescription();
  EXPECT_NE(warnings->Message.find("1 of the 400 points have a non-finite coordinate"), std::string::npos);
  vtkNew<vtkGLSLasReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkPolyData* back = reader->GetOutput();
  ASSERT_EQ(back->GetNumberOfPoints(), static_cast<vtkIdType>(n - 1));
  const std::vector<double> feature = pointArray(back, "GLSFeature"), normals = pointArray(back, "Normals");
  ASSERT_EQ(normals.size(), 3 * (n - 1)); // one 3-component array again
  for (vtkIdType i = 0, j = 0; i < static_cast<vtkIdType>(n); ++i)
  {
    if (i == 7)
    {
      continue; // the missing return
    }
    double p[3], q[3];
    tile->GetPoint(i, p);
    back->GetPoint(j, q);
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_EQ(q[a], p[a]) << i; // the same integers at the same scale and offset
    }
    for (const char* name : { "Intensity", "Classification" })
    {
      EXPECT_EQ(back->GetPointData()->GetArray(name)->GetComponent(j, 0),
        tile->GetPointData()->GetArray(name)->GetComponent(i, 0)) << name;
    }
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_EQ(back->GetPointData()->GetArray("RGB")->GetComponent(j, c),
        tile->GetPointData()->GetArray("RGB")->GetComponent(i, c));
      EXPECT_EQ(normals[3 * j + c], static_cast<double>(static_cast<float>(tile->GetPointData()->GetNormals()->GetComponent(i, c))));
    }
    EXPECT_EQ(feature[j], tile->GetPointData()->GetArray("GLSFeature")->GetComponent(i, 0));
    ++j;
  }
  auto* wkt = vtkStringArray::SafeDownCast(back->GetFieldData()->GetAbstractArray("CoordinateSystemWKT"));
  ASSERT_NE(wkt, nullptr);
  EXPECT_EQ(wkt->GetValue(0), "PROJCS[\"WGS 84 / UTM zone 32N\"]");
}

TEST(Writers, APointSetFromNoLasFileGetsAScaleItsExtentAllows)
{
  // The bunny's float32 positions, no LAS scale: 1e-10 m steps (its 0.16 m extent in 32-bit integers).
  const vtkSmartPointer<vtkPolyData> bunny = bunnyCloud();
  const std::string file = outputFile("writers-bunny.las");
  vtkNew<vtkGLSLasWriter> writer;
  writer->SetFileName(file.c_str());
  writer->SetInputData(bunny);
  ASSERT_EQ(writer->Write(), 1);
  EXPECT_NE(std::string(writer->GetDescription()).find("scale 1e-10 1e-10 1e-10, chosen"), std::string::npos)
    << writer->GetDescription();
  vtkNew<vtkGLSLasReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  ASSERT_EQ(reader->GetOutput()->GetNumberOfPoints(), bunny->GetNumberOfPoints());
  double largest = 0.0;
  for (vtkIdType i = 0; i < bunny->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    bunny->GetPoint(i, p);
    reader->GetOutput()->GetPoint(i, q);
    for (int a = 0; a < 3; ++a)
    {
      largest = std::max(largest, std::abs(p[a] - q[a]));
    }
  }
  EXPECT_LE(largest, 0.5e-10 + 1e-17);
}

TEST(Writers, APlyFileWrittenIsReadBackByVtksReaderWithItsFaces)
{
  const vtkSmartPointer<vtkPolyData> mesh = bunnyMeshWithNormals();
  const std::string file = outputFile("writers-bunny.ply");
  vtkNew<vtkGLSPlyWriter> writer;
  writer->SetFileName(file.c_str());
  writer->SetInputData(mesh);
  ASSERT_EQ(writer->Write(), 1);
  vtkNew<vtkPLYReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkPolyData* back = reader->GetOutput();
  ASSERT_EQ(back->GetNumberOfPoints(), mesh->GetNumberOfPoints());
  EXPECT_EQ(back->GetNumberOfPolys(), mesh->GetNumberOfPolys());
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); i += 97)
  {
    double p[3], q[3];
    mesh->GetPoint(i, p);
    back->GetPoint(i, q);
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_EQ(static_cast<float>(q[a]), static_cast<float>(p[a]));
      EXPECT_FLOAT_EQ(static_cast<float>(back->GetPointData()->GetNormals()->GetComponent(i, a)),
        static_cast<float>(mesh->GetPointData()->GetNormals()->GetComponent(i, a)));
    }
  }
}
