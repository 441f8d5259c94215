// vtkGLSPointCloudReader: real files (written here) read into points, vertices and the arrays their columns hold --
// Normals only when they are normals, RGB (unsigned char) for colours, Intensity (float), other named columns --
// with a warning for normals far from unit length; bad files give clear errors naming the file and the line.
#include "FilterTestUtilities.h"

#include "vtkGLSPointCloudReader.h"

#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkFieldData.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <fstream>

namespace
{

std::string writeTemp(const std::string& name, const std::string& text)
{
  const std::string path = std::string(GLS_TEST_OUTPUT_DIR) + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

struct Read
{
  vtkNew<vtkGLSPointCloudReader> reader;
  vtkSmartPointer<glstest::ErrorCatcher> errors = glstest::catchErrors(reader);
  vtkSmartPointer<glstest::ErrorCatcher> warnings = vtkSmartPointer<glstest::ErrorCatcher>::New();

  Read(const std::string& name, const std::string& text)
  {
    reader->AddObserver(vtkCommand::WarningEvent, warnings);
    reader->SetFileName(writeTemp(name, text).c_str());
    reader->Update();
  }
  vtkPolyData* output() { return reader->GetOutput(); }
  vtkPointData* arrays() { return reader->GetOutput()->GetPointData(); }
};

} // namespace

TEST(PointCloudReader, ReadsPointsNormalsAndVertices)
{
  Read r("reader-ok.xyz", "# scan\n0 0 0 0 0 1\n1 0 0 0 1 0\n0 1 0.5 0.6 0 0.8\n");
  EXPECT_TRUE(r.reader->CanReadFile(r.reader->GetFileName()));
  EXPECT_EQ(r.errors->Count, 0) << r.errors->Message;
  EXPECT_EQ(r.warnings->Count, 0) << r.warnings->Message;
  vtkPolyData* out = r.output();
  ASSERT_EQ(out->GetNumberOfPoints(), 3);
  EXPECT_EQ(out->GetPoints()->GetDataType(), VTK_DOUBLE);
  EXPECT_EQ(out->GetVerts()->GetNumberOfCells(), 3);
  double p[3];
  out->GetPoint(2, p);
  EXPECT_EQ(p[2], 0.5);
  ASSERT_NE(r.arrays()->GetNormals(), nullptr);
  EXPECT_STREQ(r.arrays()->GetNormals()->GetName(), "Normals");
  EXPECT_EQ(glstest::values(r.arrays()->GetNormals()), (std::vector<double>{ 0, 0, 1, 0, 1, 0, 0.6, 0, 0.8 }));
  EXPECT_EQ(r.arrays()->GetArray("RGB"), nullptr);
  EXPECT_STREQ(r.reader->GetColumnLayout(), "x y z nx ny nz (6 columns, no header: unit vectors, so normals)");
}

TEST(PointCloudReader, ColoursBecomeRGBAndNeverNormals)
{
  // x y z r g b without a header: colour vectors of length 100 to 400, which the reader once took for normals.
  Read r("reader-rgb.xyz", "0 0 0 255 128 0\n1 0 0 10 20 30\n0 1 0 200 200 200\n");
  EXPECT_EQ(r.errors->Count, 0) << r.errors->Message;
  ASSERT_EQ(r.output()->GetNumberOfPoints(), 3);
  EXPECT_EQ(r.arrays()->GetNormals(), nullptr);
  EXPECT_EQ(r.arrays()->GetArray("Normals"), nullptr);
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(r.arrays()->GetArray("RGB"));
  ASSERT_NE(rgb, nullptr);
  EXPECT_EQ(rgb->GetNumberOfComponents(), 3);
  EXPECT_EQ(r.arrays()->GetScalars(), rgb); // active scalars, so ParaView shows the colours
  EXPECT_EQ(glstest::values(rgb), (std::vector<double>{ 255, 128, 0, 10, 20, 30, 200, 200, 200 }));
}

TEST(PointCloudReader, LeicaPtsGivesIntensityAndRGB)
{
  Read r("reader-leica.pts", "2\n1.5 2 3 -1024 255 0 0\n4 5 6 2047 0 10 255\n");
  EXPECT_EQ(r.errors->Count, 0) << r.errors->Message;
  ASSERT_EQ(r.output()->GetNumberOfPoints(), 2);
  EXPECT_EQ(glstest::values(r.output()->GetPoints()->GetData()), (std::vector<double>{ 1.5, 2, 3, 4, 5, 6 }));
  auto* intensity = vtkFloatArray::SafeDownCast(r.arrays()->GetArray("Intensity"));
  ASSERT_NE(intensity, nullptr);
  EXPECT_EQ(glstest::values(intensity), (std::vector<double>{ -1024, 2047 }));
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(r.arrays()->GetArray("RGB"));
  ASSERT_NE(rgb, nullptr);
  EXPECT_EQ(glstest::values(rgb), (std::vector<double>{ 255, 0, 0, 0, 10, 255 }));
  EXPECT_EQ(r.arrays()->GetNormals(), nullptr);
  EXPECT_STREQ(r.reader->GetColumnLayout(),
    "x y z intensity r g b (7 columns, no header: Leica PTS); 1 point count line");

  Read four("reader-leica4.pts", "2\n1 2 3 7\n4 5 6 -8\n");
  EXPECT_EQ(four.errors->Count, 0) << four.errors->Message;
  EXPECT_EQ(glstest::values(four.arrays()->GetArray("Intensity")), (std::vector<double>{ 7, -8 }));
}

TEST(PointCloudReader, HeaderColumnsDecimalCommasAndNonUnitNormals)
{
  // A European CSV with a header: decimal commas, colours as fractions, an extra column, normals of length 2.
  Read r("reader-eu.csv", "x;y;z;nx;ny;nz;red;green;blue;time\n1,5;0;0;0;0;2;0,2;0,4;1;10,25\n"
                          "2;0;0;0;1;0;0;0;0;11\n");
  EXPECT_EQ(r.errors->Count, 0) << r.errors->Message;
  ASSERT_EQ(r.output()->GetNumberOfPoints(), 2);
  EXPECT_EQ(glstest::values(r.output()->GetPoints()->GetData()), (std::vector<double>{ 1.5, 0, 0, 2, 0, 0 }));
  EXPECT_EQ(glstest::values(r.arrays()->GetNormals()), (std::vector<double>{ 0, 0, 2, 0, 1, 0 })); // as given
  EXPECT_EQ(glstest::values(r.arrays()->GetArray("RGB")), (std::vector<double>{ 51, 102, 255, 0, 0, 0 }));
  EXPECT_EQ(glstest::pointArray(r.output(), "time"), (std::vector<double>{ 10.25, 11 }));
  EXPECT_EQ(r.warnings->Count, 1);
  EXPECT_NE(r.warnings->Message.find("reader-eu.csv: 1 of 2 normals have a length far from 1"), std::string::npos)
    << r.warnings->Message;
}

TEST(PointCloudReader, BadFilesGiveErrorsWithTheLineAndAnEmptyOutput)
{
  Read r("reader-bad.csv", "x,y,z\n1,2,3\n4,5\n");
  EXPECT_EQ(r.errors->Count, 1);
  EXPECT_NE(r.errors->Message.find("reader-bad.csv: line 3: expected 3 columns"), std::string::npos)
    << r.errors->Message;
  EXPECT_EQ(r.output()->GetNumberOfPoints(), 0);

  // A good read, then one whose columns cannot be told apart: an error with the way out, and an empty output.
  r.reader->SetFileName(writeTemp("reader-good.xyz", "0 0 0\n1 1 1\n").c_str());
  r.reader->Update();
  ASSERT_EQ(r.output()->GetNumberOfPoints(), 2);
  r.reader->SetFileName(writeTemp("reader-unclear.xyz", "0 0 0 0.5 0.5 0.5\n").c_str());
  r.reader->Update();
  EXPECT_EQ(r.errors->Count, 2);
  EXPECT_NE(r.errors->Message.find("add a header line naming the columns"), std::string::npos) << r.errors->Message;
  EXPECT_EQ(r.output()->GetNumberOfPoints(), 0);
  EXPECT_STREQ(r.reader->GetColumnLayout(), "");

  r.reader->SetFileName("/nonexistent/cloud.xyz");
  r.reader->Update();
  EXPECT_EQ(r.errors->Count, 3);
  EXPECT_NE(r.errors->Message.find("cannot be opened"), std::string::npos) << r.errors->Message;
  EXPECT_FALSE(r.reader->CanReadFile("cloud.ply"));
}

TEST(PointCloudReader, ClaimsCsvAndTxtFilesThatHoldAPointCloudOnly)
{
  // ParaView's reader factory asks CanReadFile: a .csv or .txt point cloud is ours, any other table is left to
  // ParaView's CSV reader; the other extensions are ours by name.
  vtkNew<vtkGLSPointCloudReader> reader;
  EXPECT_TRUE(reader->CanReadFile(writeTemp("claim-cloud.csv", "x,y,z,speed\n0,0,0,1\n1,0,0,2\n").c_str()));
  EXPECT_TRUE(reader->CanReadFile(writeTemp("claim-cloud.TXT", "0 0 0\n1 0 0\n0 1 0\n").c_str()));
  EXPECT_FALSE(reader->CanReadFile(writeTemp("claim-table.csv", "time,value\n0,1\n1,2\n").c_str()));
  EXPECT_FALSE(reader->CanReadFile(writeTemp("claim-names.csv", "name,x,y,z\nP1,1,2,3\n").c_str()));
  EXPECT_FALSE(reader->CanReadFile(writeTemp("claim-two.txt", "1 2\n3 4\n").c_str()));
  EXPECT_FALSE(reader->CanReadFile("/nonexistent/cloud.csv"));
  EXPECT_TRUE(reader->CanReadFile("/nonexistent/cloud.xyz"));

  // A PCL PCD file renamed .txt is claimed and read as one, its ColumnLayout saying so.
  Read r("claim-renamed-pcd.txt",
    "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\n"
    "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA ascii\n1 2 3\n4 5 6\n");
  EXPECT_TRUE(r.reader->CanReadFile(r.reader->GetFileName()));
  EXPECT_EQ(r.errors->Count, 0) << r.errors->Message;
  ASSERT_EQ(r.output()->GetNumberOfPoints(), 2);
  double p[3];
  r.output()->GetPoint(1, p);
  EXPECT_EQ(p[2], 6.0);
  EXPECT_EQ(std::string(r.reader->GetColumnLayout()).rfind("a PCL PCD file by its content: ", 0), 0u)
    << r.reader->GetColumnLayout();
  // PCL's default VIEWPOINT: a sensor at the origin, one tuple of field data (not a point array).
  vtkDataArray* sensor = r.output()->GetFieldData()->GetArray("ScannerPosition");
  ASSERT_NE(sensor, nullptr);
  ASSERT_EQ(sensor->GetNumberOfTuples(), 1);
  EXPECT_EQ(sensor->GetComponent(0, 0), 0.0);
  EXPECT_EQ(sensor->GetComponent(0, 2), 0.0);
  EXPECT_EQ(r.output()->GetPointData()->GetArray("ScannerPosition"), nullptr);
}
