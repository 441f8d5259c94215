// CGAL's PCA normal estimation (CGAL::pca_estimate_normals, k nearest neighbours, TBB-parallel), the optional peer
// column of benchmark P4. Built only when CMake finds CGAL and TBB (Debian: libcgal-dev, libtbb-dev).
#pragma once

#include <vector>

/// Unit normals (3n, unoriented) of the n interleaved positions xyz from the k nearest neighbours, on `threads`
/// threads (0: all cores).
void cgalPcaNormals(const std::vector<double>& xyz, int k, int threads, std::vector<double>& normals);
