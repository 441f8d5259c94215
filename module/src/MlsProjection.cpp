#include "gls/MlsProjection.h"

#include "gls/NeighborGrid.h"
#include "gls/Numeric.h"
#include "gls/Projection.h"

#include <cmath>
#include <vector>

namespace gls
{

bool projectPointCloud(const double* points, const double* normals, std::size_t n, const double* scales,
  const ProjectionSettings& settings, const ProjectionOutputs& out)
{
  std::vector<double> unitNormals;
  std::vector<unsigned char> admit;
  normalizeAndAdmit(points, normals, n, unitNormals, admit);
  double largestScale = 0.0;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (isFinite(scales[i]) && scales[i] > largestScale)
    {
      largestScale = scales[i];
    }
  }
  NeighborGrid grid;
  // Cells of about half the largest scale (the grid enlarges them if there would be too many).
  grid.setThreads(settings.parallel.threads);
  grid.build(points, unitNormals.data(), n, largestScale > 0.0 ? 0.5 * largestScale : 1.0, admit.data());
  const GridView& g = grid.view();
  return parallelFor(n, settings.parallel, [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t i = begin; i < end; ++i)
    {
      const Vec3 p{ points[3 * i], points[3 * i + 1], points[3 * i + 2] };
      const double t = scales[i];
      ProjectionResult r;
      const bool finitePoint = isFinite(p.x) && isFinite(p.y) && isFinite(p.z);
      if (finitePoint && isFinite(t) && t > 0.0)
      {
        r = projectOntoSurface(g, p, t, settings.minNeighbors, settings.maxIterations, settings.tolerance);
      }
      out.iterations[i] = r.iterations;
      out.converged[i] = r.valid && r.converged ? 1 : 0;
      if (r.valid)
      {
        const Vec3 d = r.position - p;
        out.points[3 * i] = r.position.x;
        out.points[3 * i + 1] = r.position.y;
        out.points[3 * i + 2] = r.position.z;
        out.normals[3 * i] = r.normal.x;
        out.normals[3 * i + 1] = r.normal.y;
        out.normals[3 * i + 2] = r.normal.z;
        out.displacement[i] = std::sqrt(squaredNorm(d));
      }
      else
      {
        for (int a = 0; a < 3; ++a)
        {
          out.points[3 * i + a] = points[3 * i + a];
          out.normals[3 * i + a] = unitNormals[3 * i + a];
        }
        out.displacement[i] = quietNaN<double>();
      }
    }
  });
}

} // namespace gls
