#include "TestClouds.h"

#include <fstream>
#include <sstream>

namespace glstest
{

std::vector<double> readObjVertices(const std::string& path)
{
  std::vector<double> xyz;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
  {
    if (line.size() > 2 && line[0] == 'v' && line[1] == ' ')
    {
      std::istringstream s(line.substr(2));
      double x, y, z;
      if (s >> x >> y >> z)
      {
        xyz.insert(xyz.end(), { x, y, z });
      }
    }
  }
  return xyz;
}

std::string dataFile(const std::string& name)
{
  return std::string(GLS_TEST_DATA_DIR) + "/" + name;
}

} // namespace glstest
