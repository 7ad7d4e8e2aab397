// SPDX-License-Identifier: MIT
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

namespace runnel {

// The 8 neighbours of a vertex of an nx × ny grid with spacing `cell`: east, west, south, north,
// then the diagonals, with the distance to each. The interior vertices are visited without a
// division or a bounds test: routing visits every vertex's neighbours several times per step.
class GridNeighbours {
 public:
  GridNeighbours(int nx, int ny, double cell = 1.0)
      : nx_(nx),
        ny_(ny),
        offset_{1, -1, nx, -nx, nx + 1, -nx + 1, nx - 1, -nx - 1},
        on_edge_(static_cast<std::size_t>(nx) * ny, 0) {
    for (int d = 0; d < 8; ++d) {
      length_[d] = d < 4 ? cell : cell * std::sqrt(2.0);
      inverse_length_[d] = 1.0 / length_[d];
    }
    for (int i = 0; i < nx; ++i)
      on_edge_[i] = on_edge_[static_cast<std::size_t>(ny - 1) * nx + i] = 1;
    for (int j = 0; j < ny; ++j) on_edge_[j * nx] = on_edge_[j * nx + nx - 1] = 1;
  }
  // f(m, d) for every neighbour m of k, d its direction (0–3 along the axes, 4–7 diagonal).
  template <class Visit>
  void visit(std::int32_t k, Visit&& f) const {
    if (!on_edge_[k]) {
      for (int d = 0; d < 8; ++d) f(k + offset_[d], d);
      return;
    }
    static constexpr int kDi[8] = {1, -1, 0, 0, 1, 1, -1, -1}, kDj[8] = {0, 0, 1, -1, 1, -1, 1, -1};
    const int i = k % nx_, j = k / nx_;
    for (int d = 0; d < 8; ++d) {
      const int a = i + kDi[d], b = j + kDj[d];
      if (a >= 0 && b >= 0 && a < nx_ && b < ny_) f(b * nx_ + a, d);
    }
  }
  // Whether k lies on the grid's border (some of its neighbours are off the grid).
  bool on_edge(std::int32_t k) const { return on_edge_[k] != 0; }
  // k's neighbour in direction d (which must lie on the grid).
  std::int32_t neighbour(std::int32_t k, int d) const { return k + offset_[d]; }
  double length(int d) const { return length_[d]; }
  double inverse_length(int d) const { return inverse_length_[d]; }

 private:
  int nx_, ny_;
  std::int32_t offset_[8];
  double length_[8], inverse_length_[8];
  std::vector<std::uint8_t> on_edge_;
};

}  // namespace runnel
