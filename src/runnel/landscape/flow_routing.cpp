// SPDX-License-Identifier: MIT
#include "runnel/landscape/flow_routing.hpp"

#include <cmath>
#include <functional>

#include "runnel/landscape/radix_heap.hpp"

namespace runnel {

void build_stack(FlowRouting& r, const std::vector<double>& cell_area) {
  const std::size_t n = r.receiver.size();
  // Donor lists (counting sort by receiver), then a depth-first walk from each base-level node.
  std::vector<std::int32_t> first(n + 1, 0), donors(n);
  for (std::size_t k = 0; k < n; ++k)
    if (r.receiver[k] != static_cast<std::int32_t>(k)) ++first[r.receiver[k] + 1];
  for (std::size_t k = 0; k < n; ++k) first[k + 1] += first[k];
  std::vector<std::int32_t> fill(first.begin(), first.end() - 1);
  for (std::size_t k = 0; k < n; ++k)
    if (r.receiver[k] != static_cast<std::int32_t>(k))
      donors[fill[r.receiver[k]]++] = static_cast<std::int32_t>(k);
  r.stack.clear();
  r.stack.reserve(n);
  std::vector<std::int32_t> pending;  // the depth-first walk's own stack
  for (std::size_t b = 0; b < n; ++b) {
    if (r.receiver[b] != static_cast<std::int32_t>(b)) continue;
    pending.push_back(static_cast<std::int32_t>(b));
    while (!pending.empty()) {
      const std::int32_t k = pending.back();
      pending.pop_back();
      r.stack.push_back(k);
      for (std::int32_t d = first[k]; d < first[k + 1]; ++d) pending.push_back(donors[d]);
    }
  }
  r.area = cell_area;
  for (std::size_t s = n; s-- > 0;) {
    const std::int32_t k = r.stack[s];
    if (r.receiver[k] != k) r.area[r.receiver[k]] += r.area[k];
  }
}

void priority_flood(std::vector<double>& filled, int nx, int ny,
                    const std::function<bool(int, int)>& is_outlet, double epsilon) {
  static const int di[8] = {1, -1, 0, 0, 1, 1, -1, -1}, dj[8] = {0, 0, 1, -1, 1, -1, 1, -1};
  const std::size_t n = filled.size();
  std::vector<bool> closed(n, false);
  RadixHeap open;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      if (is_outlet(i, j)) {
        const std::int32_t k = j * nx + i;
        closed[k] = true;
        open.push(filled[k], k);
      }
  while (!open.empty()) {
    const auto [h, k] = open.pop();
    const int i = k % nx, j = k / nx;
    for (int d = 0; d < 8; ++d) {
      const int a = i + di[d], b = j + dj[d];
      if (a < 0 || b < 0 || a >= nx || b >= ny) continue;
      const std::int32_t m = b * nx + a;
      if (closed[m]) continue;
      closed[m] = true;
      filled[m] = std::max(filled[m], h + epsilon);
      open.push(filled[m], m);
    }
  }
}

FlowRouting route_d8(const std::vector<double>& height, int nx, int ny, double cell,
                     BaseLevel base) {
  const std::size_t n = static_cast<std::size_t>(nx) * ny;
  constexpr double kEpsilon = 1e-9;
  static const int di[8] = {1, -1, 0, 0, 1, 1, -1, -1}, dj[8] = {0, 0, 1, -1, 1, -1, 1, -1};
  std::vector<double> filled(height);
  // Most of a landscape that has been eroding for a while has no pit and no flat: then the filled
  // surface is the surface, and the O(n log n) flood (most of the routing's time) is skipped.
  bool pits = false;
  for (int j = 0; j < ny && !pits; ++j)
    for (int i = 0; i < nx && !pits; ++i) {
      if (is_base_level(i, j, nx, ny, base)) continue;
      bool lower = false;
      for (int d = 0; d < 8 && !lower; ++d) {
        const int a = i + di[d], b = j + dj[d];
        if (a >= 0 && b >= 0 && a < nx && b < ny) lower = height[b * nx + a] < height[j * nx + i];
      }
      pits = !lower;
    }
  if (pits)
    priority_flood(
        filled, nx, ny, [&](int i, int j) { return is_base_level(i, j, nx, ny, base); }, kEpsilon);
  FlowRouting r;
  r.receiver.resize(n);
  r.distance.assign(n, 0.0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::int32_t k = j * nx + i;
      r.receiver[k] = k;
      if (is_base_level(i, j, nx, ny, base)) continue;
      double steepest = 0;
      for (int d = 0; d < 8; ++d) {
        const int a = i + di[d], b = j + dj[d];
        if (b < 0 || b >= ny) continue;  // a closed edge
        const std::int32_t m = b * nx + a;
        const double length = d < 4 ? cell : cell * std::sqrt(2.0);
        const double slope = (filled[k] - filled[m]) / length;
        if (slope > steepest) steepest = slope, r.receiver[k] = m, r.distance[k] = length;
      }
    }
  build_stack(r, std::vector<double>(n, cell * cell));
  return r;
}

}  // namespace runnel
