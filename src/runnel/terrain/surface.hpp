// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

#include "runnel/core/heightmap.hpp"

namespace runnel {

// The height of the terrain's triangle mesh at (x, z) in metres: the C++ reference of
// cl/terrain_sample.cl (tiles split along (i, j)–(i+1, j+1)); points outside are clamped.
double surface_height(const Heightmap& terrain, double x, double z);

// Height and unit normal at (x, z) as cl/terrain_sample.cl's terrain_surface gives them: the
// triangle's plane, and the vertex normals (terrain_normals_reference) interpolated
// barycentrically.
struct SurfacePointReference {
  double height;
  double normal[3];
};
SurfacePointReference surface_point(const Heightmap& terrain, const std::vector<float>& normals,
                                    double x, double z);

// The water's surface at (x, z) over the terrain's triangles: the surface heights (bed + depth) of
// the wet vertices (depth > 0) of the triangle holding the point, weighted as surface_height
// weights them and renormalised over the wet ones; -infinity where none of them is wet. A lake
// that ends on a steep bank keeps its level up to the bank, where bed + interpolated depth would
// rise with the bank.
double wet_surface_height(const Heightmap& terrain, const std::vector<float>& depth, double x,
                          double z);

// The Euclidean distance from (x, y, z) to the terrain's triangle mesh, exact where it is below
// `reach`; `reach` or more where no triangle is that close (only the cells within reach are
// searched).
double distance_to_surface(const Heightmap& terrain, double x, double y, double z, double reach);

// The contact surface: the terrain with every vertex raised by radius / n_y (its normal's vertical
// part, at least 0.2), as cl/terrain_sample.cl's offset_surface builds it.
Heightmap contact_surface(const Heightmap& terrain, double radius);

}  // namespace runnel
