// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

#include "runnel/core/heightmap.hpp"

namespace runnel {

// Vertex normals (physics.md §1), 3 floats per vertex, from central differences (one-sided at the
// edges). The plain C++ reference (double precision) is the oracle for cl/terrain_normals.cl and
// what shaded pictures are lit by.
std::vector<float> terrain_normals_reference(const Heightmap& terrain);

}  // namespace runnel
