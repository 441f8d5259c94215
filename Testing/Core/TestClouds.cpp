#include "TestClouds.h"

#include <array>
#include <algorithm>
#include <cstdlib>
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

Cloud sampleObjSurface(const std::string& path, std::size_t n, unsigned seed)
{
  std::vector<double> v;
  std::vector<std::array<std::size_t, 3>> triangles;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
  {
    std::istringstream s(line.size() > 2 ? line.substr(2) : std::string());
    if (line.size() > 2 && line[0] == 'v' && line[1] == ' ')
    {
      double x, y, z;
      if (s >> x >> y >> z)
      {
        v.insert(v.end(), { x, y, z });
      }
    }
    else if (line.size() > 2 && line[0] == 'f' && line[1] == ' ')
    {
      std::vector<std::size_t> corners; // "f a b c", "f a/t b/t c/t" or "f a//n ...": the vertex index before '/'
      std::string word;
      while (s >> word)
      {
        const long index = std::strtol(word.c_str(), nullptr, 10);
        if (index >= 1)
        {
          corners.push_back(static_cast<std::size_t>(index - 1));
        }
      }
      for (std::size_t k = 2; k < corners.size(); ++k)
      {
        triangles.push_back({ corners[0], corners[k - 1], corners[k] });
      }
    }
  }
  const std::size_t vertices = v.size() / 3;
  triangles.erase(std::remove_if(triangles.begin(), triangles.end(),
                    [vertices](const std::array<std::size_t, 3>& t) {
                      return t[0] >= vertices || t[1] >= vertices || t[2] >= vertices;
                    }),
    triangles.end());
  Cloud c;
  if (triangles.empty())
  {
    return c;
  }
  // Area-weighted vertex normals (the cross products summed), and the triangles' cumulative areas.
  std::vector<double> vn(v.size(), 0.0), faceNormal(3 * triangles.size()), cumulative(triangles.size());
  double total = 0.0;
  for (std::size_t f = 0; f < triangles.size(); ++f)
  {
    const double* a = &v[3 * triangles[f][0]];
    const double* b = &v[3 * triangles[f][1]];
    const double* d = &v[3 * triangles[f][2]];
    const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double w[3] = { d[0] - a[0], d[1] - a[1], d[2] - a[2] };
    const double x[3] = { u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0] };
    for (std::size_t corner : triangles[f])
    {
      for (int k = 0; k < 3; ++k)
      {
        vn[3 * corner + k] += x[k];
      }
    }
    std::copy(x, x + 3, &faceNormal[3 * f]);
    total += 0.5 * std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    cumulative[f] = total;
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  c.points.reserve(3 * n);
  c.normals.reserve(3 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const double pick = uniform(rng) * total;
    const std::size_t f = std::min<std::size_t>(
      static_cast<std::size_t>(std::lower_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin()),
      triangles.size() - 1);
    double r1 = uniform(rng), r2 = uniform(rng);
    if (r1 + r2 > 1.0)
    {
      r1 = 1.0 - r1;
      r2 = 1.0 - r2;
    }
    const double weights[3] = { 1.0 - r1 - r2, r1, r2 };
    double p[3] = { 0, 0, 0 }, nrm[3] = { 0, 0, 0 };
    for (int corner = 0; corner < 3; ++corner)
    {
      const std::size_t id = triangles[f][static_cast<std::size_t>(corner)];
      const double nl = std::sqrt(vn[3 * id] * vn[3 * id] + vn[3 * id + 1] * vn[3 * id + 1] +
        vn[3 * id + 2] * vn[3 * id + 2]);
      for (int k = 0; k < 3; ++k)
      {
        p[k] += weights[corner] * v[3 * id + k];
        nrm[k] += nl > 0.0 ? weights[corner] * vn[3 * id + k] / nl : 0.0;
      }
    }
    double l = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    if (!(l > 1e-12))
    {
      std::copy(&faceNormal[3 * f], &faceNormal[3 * f] + 3, nrm);
      l = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    }
    c.add(p[0], p[1], p[2], nrm[0] / l, nrm[1] / l, nrm[2] / l);
  }
  return c;
}

std::string dataFile(const std::string& name)
{
  return std::string(GLS_TEST_DATA_DIR) + "/" + name;
}

} // namespace glstest
