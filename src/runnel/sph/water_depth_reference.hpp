// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <vector>

namespace runnel {

// The water depth on the bed that each particle reads (cl/water_depth.cl; docs/erosion.md, "The
// water depth on the bed" and "Films"), computed plainly in double: every particle's volume V on
// the vertices of its footprint (footprint.hpp), depth_k = Σ_i V ŵ_ik / cell², then read back at
// each particle. Where the footprint holds kFilmNeighbours particles' water besides the particle's
// own, D is the footprint mean, the particle's own water included. Otherwise the particle is a
// film: D is read on the finest coarser level (vertices 2^l cells apart, each the mean of its block
// of fine vertices, the footprint scaled by 2^l) whose footprint holds kFilmNeighbours other
// particles' water, without the particle's own. Where none does, the particle is a drop on its own,
// not a sample of a sheet, and D is its fine footprint mean again.
inline constexpr double kFilmNeighbours = 8.0;
// At most this many coarser levels (a footprint 64 times as wide), fewer on a small terrain: the
// coarsest keeps at least two vertices along each side.
inline constexpr int kFilmLevelsMax = 6;
int film_levels(int nx, int ny);
// Vertices along a side of `side` vertices on level `level` (each level halves it, rounding up).
int film_level_side(int side, int level);
// The vertices of the fine grid and all its coarser levels together.
std::size_t film_level_vertices(int nx, int ny);

struct DepthReading {
  double depth = 0;      // m, D
  int level = 0;         // the level D was read on: ≥ 1 a film that a coarser level resolved
  bool resolved = true;  // some level held kFilmNeighbours other particles' water
  // The fine footprint's water in particles, the particle's own included.
  double fine_particles = 0;
};

std::vector<DepthReading> water_depth_reference(const std::vector<float>& x,
                                                const std::vector<float>& z, int nx, int ny,
                                                double cell, double radius, double volume);

}  // namespace runnel
