#include "gls/CoincidentPoints.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace gls
{

CoincidentPoints findCoincidentPoints(const double* xyz, std::size_t n)
{
  CoincidentPoints c;
  std::vector<std::uint64_t> order(n);
  std::iota(order.begin(), order.end(), std::uint64_t(0));
  const auto finite = [xyz](std::uint64_t i) {
    return std::isfinite(xyz[3 * i]) && std::isfinite(xyz[3 * i + 1]) && std::isfinite(xyz[3 * i + 2]);
  };
  // Lexicographic order of the coordinates, the input order among equals (non-finite points last, never equal).
  std::stable_sort(order.begin(), order.end(), [&](std::uint64_t a, std::uint64_t b) {
    const bool fa = finite(a), fb = finite(b);
    if (fa != fb)
    {
      return fa;
    }
    if (!fa)
    {
      return false;
    }
    for (int k = 0; k < 3; ++k)
    {
      if (xyz[3 * a + k] != xyz[3 * b + k])
      {
        return xyz[3 * a + k] < xyz[3 * b + k];
      }
    }
    return false;
  });
  const auto same = [&](std::uint64_t a, std::uint64_t b) {
    return finite(a) && finite(b) && xyz[3 * a] == xyz[3 * b] && xyz[3 * a + 1] == xyz[3 * b + 1] &&
      xyz[3 * a + 2] == xyz[3 * b + 2];
  };
  // first[i]: the first point (input order) of i's group.
  std::vector<std::uint64_t> first(n);
  for (std::size_t s = 0; s < n;)
  {
    std::size_t e = s + 1;
    while (e < n && same(order[s], order[e]))
    {
      ++e;
    }
    for (std::size_t k = s; k < e; ++k)
    {
      first[order[k]] = order[s]; // stable: order[s] is the group's earliest point
    }
    s = e;
  }
  // Distinct positions numbered in the input order of their first point.
  c.representative.assign(n, 0);
  std::vector<std::uint64_t> groupSize;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (first[i] == i)
    {
      c.representative[i] = c.distinct.size();
      c.distinct.push_back(i);
      groupSize.push_back(0);
    }
    else
    {
      c.representative[i] = c.representative[first[i]];
    }
    ++groupSize[c.representative[i]];
  }
  c.copyStart.assign(c.distinct.size() + 1, 0);
  for (std::size_t u = 0; u < c.distinct.size(); ++u)
  {
    c.copyStart[u + 1] = c.copyStart[u] + groupSize[u];
  }
  c.copies.assign(n, 0);
  std::vector<std::uint64_t> fill(c.copyStart.begin(), c.copyStart.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
  {
    c.copies[fill[c.representative[i]]++] = i;
  }
  return c;
}

std::vector<double> distinctValues(const CoincidentPoints& c, const double* values, int width)
{
  const std::size_t w = static_cast<std::size_t>(width);
  std::vector<double> out(w * c.distinct.size());
  for (std::size_t u = 0; u < c.distinct.size(); ++u)
  {
    std::copy(values + w * c.distinct[u], values + w * c.distinct[u] + w, out.begin() + static_cast<long>(w * u));
  }
  return out;
}

std::vector<double> mergedNormals(const CoincidentPoints& c, const double* normals)
{
  std::vector<double> out = distinctValues(c, normals, 3);
  for (std::size_t u = 0; u < c.distinct.size(); ++u)
  {
    const std::uint64_t* begin = c.copies.data() + c.copyStart[u];
    const std::uint64_t* end = c.copies.data() + c.copyStart[u + 1];
    const double* first = normals + 3 * *begin;
    const bool allEqual = std::all_of(begin, end, [&](std::uint64_t i) {
      return normals[3 * i] == first[0] && normals[3 * i + 1] == first[1] && normals[3 * i + 2] == first[2];
    });
    if (allEqual)
    {
      continue;
    }
    double sum[3] = { 0.0, 0.0, 0.0 };
    for (const std::uint64_t* i = begin; i != end; ++i)
    {
      const double* m = normals + 3 * *i;
      const double len = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
      if (len > 0.0 && std::isfinite(len))
      {
        for (int k = 0; k < 3; ++k)
        {
          sum[k] += m[k] / len;
        }
      }
    }
    const double len = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
    for (int k = 0; k < 3; ++k)
    {
      out[3 * u + k] = len > 1e-12 ? sum[k] / len : 0.0;
    }
  }
  return out;
}

void scatterToCopies(const CoincidentPoints& c, const double* values, int width, double* out)
{
  const std::size_t w = static_cast<std::size_t>(width);
  for (std::size_t i = 0; i < c.representative.size(); ++i)
  {
    std::copy(values + w * c.representative[i], values + w * c.representative[i] + w, out + w * i);
  }
}

} // namespace gls
