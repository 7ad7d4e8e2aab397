// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

namespace runnel {

// The weight along one axis of a vertex at distance d: (1 − (d/R)²)² within R, 0 beyond.
double footprint_axis_weight(double d, double radius);

// The C++ reference of cl/footprint.cl: the vertices within `radius` of (x, z) on an nx × ny grid
// of spacing `cell`, with their normalised weights (Σ = 1), the product of (1 − (d/R)²)² along x
// and z.
struct FootprintWeight {
  int i, j;
  double weight;
};
std::vector<FootprintWeight> footprint_weights(double x, double z, int nx, int ny, double cell,
                                               double radius);

// The water depth a lone particle of volume V reads at (x, z) (cl/water_depth.cl): its volume
// counted on its footprint's vertices and read back with the same weights, V·Σ_k ŵ_k² / cell².
double lone_particle_depth(double volume, double x, double z, int nx, int ny, double cell,
                           double radius);

}  // namespace runnel
