// SPDX-License-Identifier: MIT
// Shared by the generator families (generators_*.cpp): the helpers and each family's entry points.
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "runnel/terrain/generators.hpp"

namespace runnel::generator_util {

inline constexpr double kDeg = M_PI / 180.0;

// The larger horizontal side of the terrain, m.
inline double extent(const GeneratorRequest& r) {
  return (std::max(r.nx, r.ny) - 1) * r.cell;
}

// Rescales heights linearly to [0, relief_m].
void normalise(Heightmap& t, double relief_m);

// Fills every vertex from f(x, z) with x, z in metres.
template <typename F>
Heightmap from_function(const GeneratorRequest& r, F f) {
  Heightmap t(r.nx, r.ny, r.cell);
  for (int j = 0; j < r.ny; ++j) {
    for (int i = 0; i < r.nx; ++i) t.at(i, j) = static_cast<float>(f(i * r.cell, j * r.cell));
  }
  return t;
}

// A site of the Voronoi RMP generator: its position (m), its probe (the height of its ridges, ½ to
// 1) and its jittered-grid cell (a, b).
struct RidgeSite {
  double x, z, probe;
  int a, b;
};
// The sites of magnification `level` (the tests compute the Voronoi edges from them by brute
// force).
std::vector<RidgeSite> rmp_voronoi_sites(const GeneratorRequest& r, int level);

// The families (docs/generators.md).
Heightmap midpoint(const GeneratorRequest& r);              // generators_subdivision.cpp
Heightmap successive_additions(const GeneratorRequest& r);  // generators_subdivision.cpp
Heightmap value_noise_terrain(const GeneratorRequest& r);   // generators_noise.cpp
Heightmap turbulence(const GeneratorRequest& r);            // generators_noise.cpp
Heightmap multifractal(const GeneratorRequest& r);          // generators_noise.cpp
Heightmap hybrid_multifractal(const GeneratorRequest& r);   // generators_noise.cpp
Heightmap hetero_terrain(const GeneratorRequest& r);        // generators_noise.cpp
Heightmap varying_hurst(const GeneratorRequest& r);         // generators_noise.cpp
Heightmap spectral(const GeneratorRequest& r);              // generators_spectral.cpp
Heightmap circles(const GeneratorRequest& r);               // generators_ridges.cpp
Heightmap rmp_voronoi(const GeneratorRequest& r);           // generators_ridges.cpp
Heightmap rmp_graph(const GeneratorRequest& r);             // generators_ridges.cpp

}  // namespace runnel::generator_util
