// Samples a triangle mesh uniformly by area into a point cloud whose normals are interpolated (barycentric) from
// the mesh's vertex normals: the benchmark clouds of a given size made from the bundled models.
#pragma once

#include "vtkSmartPointer.h"

#include <cstdint>
#include <string>

class vtkPolyData;

/// Reads an OBJ/PLY mesh, computes area-weighted vertex normals (the file's face orientation), and returns `count`
/// points (vertex cells, active normals "Normals"); deterministic for a given seed. Null if the file cannot be read.
vtkSmartPointer<vtkPolyData> sampleMeshSurface(const std::string& path, std::int64_t count, std::uint64_t seed);
