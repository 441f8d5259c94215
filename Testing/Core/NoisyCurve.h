// The paper's Figure 9 case as a test fixture: a closed wavy 2D curve r(theta) = 1 + a cos(f theta) whose four
// quadrants carry different corruption -- A: noise on positions (sigmaA, along the normal) and normals; B: noise on
// positions (sigmaB); C: noise on normals only; D: clean -- plus the exact distance to the clean curve and the
// exact normal there, to score a denoiser per region. Seeded, deterministic.
#pragma once

#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

namespace glstest
{

struct NoisyCurveSpec
{
  std::size_t count = 4000;   ///< samples, equally spaced in theta
  double amplitude = 0.05;    ///< a
  double frequency = 16.0;    ///< f (waves per turn)
  double sigmaA = 0.015;      ///< position noise in A (length; the curve's mean radius is 1)
  double sigmaB = 0.003;      ///< position noise in B
  double normalNoiseDegrees = 10.0; ///< standard deviation of the normal rotation in A and C
  unsigned seed = 1;
};

class NoisyCurve
{
public:
  explicit NoisyCurve(const NoisyCurveSpec& spec)
    : Spec(spec)
  {
    std::mt19937_64 rng(spec.seed);
    std::normal_distribution<double> unit(0.0, 1.0);
    const double angleSigma = spec.normalNoiseDegrees * M_PI / 180.0;
    for (std::size_t i = 0; i < spec.count; ++i)
    {
      const double th = 2.0 * M_PI * static_cast<double>(i) / static_cast<double>(spec.count);
      double x[3], n[3];
      this->evaluate(th, x, n);
      const int r = static_cast<int>(th / (M_PI / 2.0));
      const double positionNoise = unit(rng) * (r == 0 ? spec.sigmaA : (r == 1 ? spec.sigmaB : 0.0));
      const double angle = unit(rng) * ((r == 0 || r == 2) ? angleSigma : 0.0);
      Theta.push_back(th);
      Region.push_back(r);
      CleanNormals.insert(CleanNormals.end(), { n[0], n[1], 0.0 });
      Points.insert(Points.end(), { x[0] + positionNoise * n[0], x[1] + positionNoise * n[1], 0.0 });
      const double c = std::cos(angle), s = std::sin(angle);
      Normals.insert(Normals.end(), { c * n[0] - s * n[1], s * n[0] + c * n[1], 0.0 });
    }
  }

  std::size_t size() const { return Theta.size(); }
  /// Mean sample spacing along the curve (length).
  double spacing() const { return this->length() / static_cast<double>(this->Spec.count); }

  /// Distance from q (z ignored) to the clean curve, and the clean unit normal at the closest point.
  double distance(const double* q, double* normal) const
  {
    // Coarse search around q's polar angle, then Newton on theta for |x(theta) - q|^2.
    const double phi = std::atan2(q[1], q[0]);
    double best = 1e300, bestTheta = phi;
    for (int k = -200; k <= 200; ++k)
    {
      const double th = phi + 0.002 * k;
      double x[3], n[3];
      this->evaluate(th, x, n);
      const double d2 = (x[0] - q[0]) * (x[0] - q[0]) + (x[1] - q[1]) * (x[1] - q[1]);
      if (d2 < best)
      {
        best = d2;
        bestTheta = th;
      }
    }
    double th = bestTheta;
    for (int it = 0; it < 30; ++it)
    {
      // g(th) = (x - q).x', g' = |x'|^2 + (x - q).x'' by central differences of the analytic curve.
      const double h = 1e-5;
      double a[3], b[3], c[3], n[3];
      this->evaluate(th - h, a, n);
      this->evaluate(th, b, n);
      this->evaluate(th + h, c, n);
      const double d1x = (c[0] - a[0]) / (2 * h), d1y = (c[1] - a[1]) / (2 * h);
      const double d2x = (c[0] - 2 * b[0] + a[0]) / (h * h), d2y = (c[1] - 2 * b[1] + a[1]) / (h * h);
      const double g = (b[0] - q[0]) * d1x + (b[1] - q[1]) * d1y;
      const double dg = d1x * d1x + d1y * d1y + (b[0] - q[0]) * d2x + (b[1] - q[1]) * d2y;
      const double step = dg > 0 ? g / dg : 0.0;
      th -= step;
      if (std::abs(step) < 1e-14)
      {
        break;
      }
    }
    double x[3];
    this->evaluate(th, x, normal);
    return std::hypot(x[0] - q[0], x[1] - q[1]);
  }

  /// Per-region scores of a result (positions and normals, n interleaved triples).
  struct Scores
  {
    double positionRms[4];   ///< RMS distance to the clean curve (length) per region A..D
    double normalRmsDegrees[4]; ///< RMS angle to the clean normal, up to sign (degrees)
    double totalPositionRms; ///< over all points
    double totalNormalRmsDegrees;
    double cleanInteriorMaxMove; ///< largest move of a D point farther than 0.35 rad from A and C (length)
    double cleanInteriorRmsMove; ///< RMS move of those points (length)
  };

  Scores score(const double* points, const double* normals) const
  {
    Scores s{};
    double sum[4] = { 0, 0, 0, 0 }, angle[4] = { 0, 0, 0, 0 };
    int count[4] = { 0, 0, 0, 0 };
    double cleanSum = 0.0;
    int cleanCount = 0;
    for (std::size_t i = 0; i < this->size(); ++i)
    {
      double n[3];
      const double d = this->distance(points + 3 * i, n);
      const double* m = normals + 3 * i;
      const double len = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
      const double cosine = std::min(1.0, std::abs(m[0] * n[0] + m[1] * n[1]) / len);
      const double a = std::acos(cosine) * 180.0 / M_PI;
      const int r = this->Region[i];
      sum[r] += d * d;
      angle[r] += a * a;
      count[r] += 1;
      const double th = this->Theta[i];
      if (r == 3 && th > 1.5 * M_PI + 0.35 && th < 2.0 * M_PI - 0.35)
      {
        const double move = std::sqrt(std::pow(points[3 * i] - this->Points[3 * i], 2) +
          std::pow(points[3 * i + 1] - this->Points[3 * i + 1], 2) +
          std::pow(points[3 * i + 2] - this->Points[3 * i + 2], 2));
        s.cleanInteriorMaxMove = std::max(s.cleanInteriorMaxMove, move);
        cleanSum += move * move;
        cleanCount += 1;
      }
    }
    double all = 0, allAngle = 0;
    for (int r = 0; r < 4; ++r)
    {
      s.positionRms[r] = std::sqrt(sum[r] / count[r]);
      s.normalRmsDegrees[r] = std::sqrt(angle[r] / count[r]);
      all += sum[r];
      allAngle += angle[r];
    }
    s.totalPositionRms = std::sqrt(all / static_cast<double>(this->size()));
    s.cleanInteriorRmsMove = std::sqrt(cleanSum / cleanCount);
    s.totalNormalRmsDegrees = std::sqrt(allAngle / static_cast<double>(this->size()));
    return s;
  }

  std::vector<double> Points, Normals, CleanNormals, Theta;
  std::vector<int> Region; ///< 0 = A, 1 = B, 2 = C, 3 = D

private:
  void evaluate(double th, double* x, double* n) const
  {
    const double a = this->Spec.amplitude, f = this->Spec.frequency;
    const double r = 1.0 + a * std::cos(f * th), dr = -a * f * std::sin(f * th);
    x[0] = r * std::cos(th);
    x[1] = r * std::sin(th);
    x[2] = 0.0;
    double tx = dr * std::cos(th) - r * std::sin(th), ty = dr * std::sin(th) + r * std::cos(th);
    const double len = std::hypot(tx, ty);
    n[0] = ty / len; // outward for a counter-clockwise curve
    n[1] = -tx / len;
    n[2] = 0.0;
  }
  double length() const
  {
    double L = 0.0, prev[3], x[3], n[3];
    this->evaluate(0.0, prev, n);
    for (int k = 1; k <= 100000; ++k)
    {
      this->evaluate(2.0 * M_PI * k / 100000.0, x, n);
      L += std::hypot(x[0] - prev[0], x[1] - prev[1]);
      prev[0] = x[0];
      prev[1] = x[1];
    }
    return L;
  }
  NoisyCurveSpec Spec;
};

} // namespace glstest
