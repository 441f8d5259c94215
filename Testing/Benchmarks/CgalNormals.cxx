#include "CgalNormals.h"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/pca_estimate_normals.h>
#include <CGAL/property_map.h>

#include <tbb/global_control.h>

#include <memory>
#include <utility>

void cgalPcaNormals(const std::vector<double>& xyz, int k, int threads, std::vector<double>& normals)
{
  using Kernel = CGAL::Simple_cartesian<double>;
  using PointAndNormal = std::pair<Kernel::Point_3, Kernel::Vector_3>;
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0)
  {
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
  }
  const std::size_t n = xyz.size() / 3;
  std::vector<PointAndNormal> cloud(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    cloud[i].first = Kernel::Point_3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  }
  CGAL::pca_estimate_normals<CGAL::Parallel_if_available_tag>(cloud, static_cast<unsigned int>(k),
    CGAL::parameters::point_map(CGAL::First_of_pair_property_map<PointAndNormal>())
      .normal_map(CGAL::Second_of_pair_property_map<PointAndNormal>()));
  normals.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    normals[3 * i] = cloud[i].second.x();
    normals[3 * i + 1] = cloud[i].second.y();
    normals[3 * i + 2] = cloud[i].second.z();
  }
}
