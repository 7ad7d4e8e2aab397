// SPDX-License-Identifier: MIT
#include "runnel/sph/water_depth_reference.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/sph/footprint.hpp"

namespace runnel {

int film_levels(int nx, int ny) {
  int levels = 0;
  while (levels < kFilmLevelsMax && (std::min(nx, ny) + 1) / 2 >= 2) {
    nx = (nx + 1) / 2, ny = (ny + 1) / 2;
    ++levels;
  }
  return levels;
}

int film_level_side(int side, int level) {
  for (int l = 0; l < level; ++l) side = (side + 1) / 2;
  return side;
}

std::size_t film_level_vertices(int nx, int ny) {
  std::size_t vertices = 0;
  for (int l = 0; l <= film_levels(nx, ny); ++l)
    vertices += static_cast<std::size_t>(film_level_side(nx, l)) * film_level_side(ny, l);
  return vertices;
}

namespace {

struct Level {
  int nx, ny, span;  // span: fine cells between two of its vertices
  int fine_nx, fine_ny;
  std::vector<double> depth;  // m, the mean of each vertex's block of fine vertices
  // The area of vertex (i, j)'s block: span² fine cells, fewer where the grid's edge cuts it.
  double block_area(int i, int j, double cell) const {
    return (std::min(fine_nx, span * (i + 1)) - span * i) *
           (std::min(fine_ny, span * (j + 1)) - span * j) * cell * cell;
  }
};

struct Reading {
  double depth, own;
};

Reading read_level(const Level& level, double cell, double radius, double volume, double x,
                   double z) {
  const double c = cell * level.span, r = radius * level.span;
  const double lx = x - 0.5 * (level.span - 1) * cell, lz = z - 0.5 * (level.span - 1) * cell;
  const int i0 = std::max(0, static_cast<int>(std::ceil((lx - r) / c)));
  const int i1 = std::min(level.nx - 1, static_cast<int>(std::floor((lx + r) / c)));
  const int j0 = std::max(0, static_cast<int>(std::ceil((lz - r) / c)));
  const int j1 = std::min(level.ny - 1, static_cast<int>(std::floor((lz + r) / c)));
  double sum = 0, weights = 0, squares = 0;
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      const double w = footprint_axis_weight(j * c - lz, r) * footprint_axis_weight(i * c - lx, r);
      const double area = level.block_area(i, j, cell);
      sum += w * level.depth[static_cast<std::size_t>(j) * level.nx + i];
      weights += w;
      squares += w * w / area;
    }
  }
  if (!(weights > 0)) return {0, 0};
  return {sum / weights, volume * squares / (weights * weights)};
}

}  // namespace

std::vector<DepthReading> water_depth_reference(const std::vector<float>& x,
                                                const std::vector<float>& z, int nx, int ny,
                                                double cell, double radius, double volume) {
  std::vector<Level> levels{
      {nx, ny, 1, nx, ny, std::vector<double>(static_cast<std::size_t>(nx) * ny)}};
  for (std::size_t p = 0; p < x.size(); ++p) {
    for (const FootprintWeight& w : footprint_weights(x[p], z[p], nx, ny, cell, radius))
      levels[0].depth[static_cast<std::size_t>(w.j) * nx + w.i] +=
          volume * w.weight / (cell * cell);
  }
  for (int l = 1; l <= film_levels(nx, ny); ++l) {
    const Level& below = levels.back();
    Level level{(below.nx + 1) / 2, (below.ny + 1) / 2, below.span * 2, nx, ny, {}};
    level.depth.assign(static_cast<std::size_t>(level.nx) * level.ny, 0.0);
    for (int J = 0; J < level.ny; ++J) {
      for (int I = 0; I < level.nx; ++I) {
        const int i_end = std::min(nx, level.span * (I + 1)),
                  j_end = std::min(ny, level.span * (J + 1));
        double sum = 0;
        for (int j = level.span * J; j < j_end; ++j)
          for (int i = level.span * I; i < i_end; ++i)
            sum += levels[0].depth[static_cast<std::size_t>(j) * nx + i];
        level.depth[static_cast<std::size_t>(J) * level.nx + I] =
            sum * cell * cell / level.block_area(I, J, cell);
      }
    }
    levels.push_back(std::move(level));
  }
  std::vector<DepthReading> out(x.size());
  for (std::size_t p = 0; p < x.size(); ++p) {
    DepthReading& d = out[p];
    const Reading fine = read_level(levels[0], cell, radius, volume, x[p], z[p]);
    d.depth = fine.depth;
    d.fine_particles = fine.own > 0 ? fine.depth / fine.own : 0;
    if (fine.depth - fine.own >= kFilmNeighbours * fine.own) continue;
    d.resolved = false;
    for (std::size_t l = 1; l < levels.size() && !d.resolved; ++l) {
      const Reading r = read_level(levels[l], cell, radius, volume, x[p], z[p]);
      d.resolved = r.depth - r.own >= kFilmNeighbours * r.own;
      if (d.resolved) d.depth = r.depth - r.own, d.level = static_cast<int>(l);
    }
  }
  return out;
}

}  // namespace runnel
