#include "PeerAgreement.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace
{

/// The q-quantile (0..1) of v by the nearest rank on a sorted copy; 0 for an empty v.
double quantile(std::vector<double> v, double q)
{
  if (v.empty())
  {
    return 0.0;
  }
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

double pearson(const std::vector<double>& a, const std::vector<double>& b)
{
  const double n = static_cast<double>(a.size());
  const double ma = std::accumulate(a.begin(), a.end(), 0.0) / n;
  const double mb = std::accumulate(b.begin(), b.end(), 0.0) / n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : 0.0;
}

/// Ranks 0..n-1 of v, ties sharing their mean rank.
std::vector<double> ranks(const std::vector<double>& v)
{
  std::vector<std::size_t> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return v[i] < v[j]; });
  std::vector<double> r(v.size());
  for (std::size_t i = 0; i < order.size();)
  {
    std::size_t j = i;
    while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]])
    {
      ++j;
    }
    for (std::size_t k = i; k <= j; ++k)
    {
      r[order[k]] = 0.5 * static_cast<double>(i + j);
    }
    i = j + 1;
  }
  return r;
}

/// The angle in degrees between u[i..i+2] and +/- v[i..i+2]; NaN when either is zero or not finite.
double angleUpToSign(const double* u, const double* v)
{
  const double dot = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  const double nu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  const double nv = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!std::isfinite(dot) || !(nu > 0) || !(nv > 0))
  {
    return std::nan("");
  }
  return std::acos(std::min(1.0, std::abs(dot) / (nu * nv))) * 180.0 / M_PI;
}

} // namespace

std::vector<std::size_t> pointsApartBy(const std::vector<double>& u, const std::vector<double>& v, double degrees)
{
  std::vector<std::size_t> apart;
  for (std::size_t i = 0; i + 2 < u.size() && i + 2 < v.size(); i += 3)
  {
    if (angleUpToSign(&u[i], &v[i]) > degrees)
    {
      apart.push_back(i / 3);
    }
  }
  return apart;
}

AngleAgreement angleAgreement(const std::vector<double>& u, const std::vector<double>& v)
{
  std::vector<double> degrees;
  degrees.reserve(u.size() / 3);
  for (std::size_t i = 0; i + 2 < u.size() && i + 2 < v.size(); i += 3)
  {
    const double a = angleUpToSign(&u[i], &v[i]);
    if (std::isfinite(a))
    {
      degrees.push_back(a);
    }
  }
  AngleAgreement a;
  a.compared = static_cast<long long>(degrees.size());
  a.aboveOneDegree = std::count_if(degrees.begin(), degrees.end(), [](double d) { return d > 1.0; });
  a.p50 = quantile(degrees, 0.5);
  a.p90 = quantile(degrees, 0.9);
  a.p99 = quantile(degrees, 0.99);
  a.max = degrees.empty() ? 0.0 : *std::max_element(degrees.begin(), degrees.end());
  return a;
}

CurvatureAgreement curvatureAgreement(const double* gls, const double* peer, std::size_t n, std::size_t stride)
{
  std::vector<double> a, b, ratio;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double x = gls[i * stride], y = peer[i * stride];
    if (std::isfinite(x) && std::isfinite(y))
    {
      a.push_back(x);
      b.push_back(y);
      if (x != 0.0)
      {
        ratio.push_back(y / x);
      }
    }
  }
  CurvatureAgreement c;
  c.compared = static_cast<long long>(a.size());
  if (a.size() < 2)
  {
    return c;
  }
  c.medianGls = quantile(a, 0.5);
  c.medianPeer = quantile(b, 0.5);
  c.medianRatio = quantile(ratio, 0.5);
  c.pearson = pearson(a, b);
  c.spearman = pearson(ranks(a), ranks(b));
  return c;
}
