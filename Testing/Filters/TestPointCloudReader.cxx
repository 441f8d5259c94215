// vtkGLSPointCloudReader: a real file with normals read into points, vertices and active normals; bad files give
// clear errors naming the file and the line.
#include "FilterTestUtilities.h"

#include "vtkGLSPointCloudReader.h"

#include "vtkCellArray.h"
#include "vtkPointData.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

namespace
{

std::string writeTemp(const std::string& name, const std::string& text)
{
  const std::string path = std::string(GLS_TEST_OUTPUT_DIR) + "/" + name;
  std::ofstream(path) << text;
  return path;
}

} // namespace

TEST(PointCloudReader, ReadsPointsNormalsAndVertices)
{
  vtkNew<vtkGLSPointCloudReader> r;
  r->SetFileName(writeTemp("reader-ok.xyz", "# scan\n0 0 0 0 0 2\n1 0 0 0 0 1\n0 1 0.5 1 0 0\n").c_str());
  EXPECT_TRUE(r->CanReadFile(r->GetFileName()));
  r->Update();
  vtkPolyData* out = r->GetOutput();
  ASSERT_EQ(out->GetNumberOfPoints(), 3);
  EXPECT_EQ(out->GetVerts()->GetNumberOfCells(), 3);
  double p[3];
  out->GetPoint(2, p);
  EXPECT_EQ(p[2], 0.5);
  const auto n = glstest::values(out->GetPointData()->GetNormals());
  EXPECT_EQ(n, (std::vector<double>{ 0, 0, 2, 0, 0, 1, 1, 0, 0 })); // as given, not normalized
}

TEST(PointCloudReader, BadFilesGiveErrorsWithTheLine)
{
  vtkNew<vtkGLSPointCloudReader> r;
  auto errors = glstest::catchErrors(r);
  r->SetFileName(writeTemp("reader-bad.csv", "x,y,z\n1,2,3\n4,5\n").c_str());
  r->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->Message.find("reader-bad.csv: line 3: expected 3 columns"), std::string::npos)
    << errors->Message;
  EXPECT_EQ(r->GetOutput()->GetNumberOfPoints(), 0);
  r->SetFileName("/nonexistent/cloud.xyz");
  r->Update();
  EXPECT_EQ(errors->Count, 2);
  EXPECT_NE(errors->Message.find("cannot be opened"), std::string::npos) << errors->Message;
  EXPECT_FALSE(r->CanReadFile("cloud.ply"));
}
