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

void sampleTrianglesByArea(const std::vector<double>& xyz, const std::vector<double>& vertexNormals,
  const std::vector<std::array<std::size_t, 3>>& triangles, std::size_t count, std::uint64_t seed, double* points,
  double* normals)
{
  if (triangles.empty())
  {
    return;
  }
  std::vector<double> cumulative(triangles.size());
  double total = 0.0;
  auto faceNormal = [&](std::size_t f, double* x) {
    const double* a = &xyz[3 * triangles[f][0]];
    const double* b = &xyz[3 * triangles[f][1]];
    const double* c = &xyz[3 * triangles[f][2]];
    const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    x[0] = u[1] * v[2] - u[2] * v[1];
    x[1] = u[2] * v[0] - u[0] * v[2];
    x[2] = u[0] * v[1] - u[1] * v[0];
  };
  for (std::size_t f = 0; f < triangles.size(); ++f)
  {
    double x[3];
    faceNormal(f, x);
    total += 0.5 * std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    cumulative[f] = total;
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (std::size_t i = 0; i < count; ++i)
  {
    const double r = uniform(rng) * total;
    const std::size_t f = std::min<std::size_t>(
      static_cast<std::size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), r) - cumulative.begin()),
      triangles.size() - 1);
    double s = uniform(rng), w = uniform(rng);
    if (s + w > 1.0)
    {
      s = 1.0 - s;
      w = 1.0 - w;
    }
    const double bary[3] = { 1.0 - s - w, s, w };
    double* p = points + 3 * i;
    double* n = normals + 3 * i;
    for (int a = 0; a < 3; ++a)
    {
      p[a] = 0.0;
      n[a] = 0.0;
    }
    for (int k = 0; k < 3; ++k)
    {
      const std::size_t corner = triangles[f][static_cast<std::size_t>(k)];
      for (int a = 0; a < 3; ++a)
      {
        p[a] += bary[k] * xyz[3 * corner + static_cast<std::size_t>(a)];
        n[a] += bary[k] * vertexNormals[3 * corner + static_cast<std::size_t>(a)];
      }
    }
    double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 1e-12))
    {
      faceNormal(f, n);
      len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
    for (int a = 0; a < 3; ++a)
    {
      n[a] /= len;
    }
  }
}

Cloud sampleObjSurface(const std::string& path, std::size_t n, std::uint64_t seed)
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
  // Area-weighted vertex normals: the faces' cross products summed at their corners, then normalized.
  std::vector<double> vn(v.size(), 0.0);
  for (const std::array<std::size_t, 3>& t : triangles)
  {
    const double* a = &v[3 * t[0]];
    const double* b = &v[3 * t[1]];
    const double* d = &v[3 * t[2]];
    const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double w[3] = { d[0] - a[0], d[1] - a[1], d[2] - a[2] };
    const double x[3] = { u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0] };
    for (std::size_t corner : t)
    {
      for (int k = 0; k < 3; ++k)
      {
        vn[3 * corner + static_cast<std::size_t>(k)] += x[k];
      }
    }
  }
  for (std::size_t i = 0; i < vertices; ++i)
  {
    const double l = std::sqrt(vn[3 * i] * vn[3 * i] + vn[3 * i + 1] * vn[3 * i + 1] + vn[3 * i + 2] * vn[3 * i + 2]);
    for (int k = 0; k < 3; ++k)
    {
      vn[3 * i + static_cast<std::size_t>(k)] = l > 0.0 ? vn[3 * i + static_cast<std::size_t>(k)] / l : 0.0;
    }
  }
  c.points.resize(3 * n);
  c.normals.resize(3 * n);
  sampleTrianglesByArea(v, vn, triangles, n, seed, c.points.data(), c.normals.data());
  return c;
}

double boxDiagonal(const std::vector<double>& xyz)
{
  double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
  for (std::size_t i = 0; i < xyz.size(); ++i)
  {
    lo[i % 3] = std::min(lo[i % 3], xyz[i]);
    hi[i % 3] = std::max(hi[i % 3], xyz[i]);
  }
  return std::sqrt(
    (hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

std::string dataFile(const std::string& name)
{
  return std::string(GLS_TEST_DATA_DIR) + "/" + name;
}

} // namespace glstest
