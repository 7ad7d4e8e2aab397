// SPDX-License-Identifier: MIT
#include "runnel/terrain/ray_pick.hpp"

#include <cmath>
#include <limits>

namespace runnel {
namespace {

struct Vec {
  double x, y, z;
};
Vec sub(Vec a, Vec b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
Vec cross(Vec a, Vec b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(Vec a, Vec b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

// Möller–Trumbore for a ray crossing the triangle from above (det < 0, see collide.cl); t or −1.
double moller_trumbore(Vec o, Vec d, Vec v0, Vec v1, Vec v2) {
  const Vec e1 = sub(v1, v0), e2 = sub(v2, v0), p = cross(d, e2);
  const double det = dot(e1, p);
  if (!(det < 0)) return -1;
  const Vec s = sub(o, v0);
  const double u = dot(s, p) / det;
  if (u < 0 || u > 1) return -1;
  const Vec q = cross(s, e1);
  const double v = dot(d, q) / det;
  if (v < 0 || u + v > 1) return -1;
  const double t = dot(e2, q) / det;
  return t >= 0 ? t : -1;
}

}  // namespace

std::optional<RayHit> pick_terrain(const Heightmap& t, const double origin[3],
                                   const double direction[3]) {
  const Vec o{origin[0], origin[1], origin[2]}, d{direction[0], direction[1], direction[2]};
  const double c = t.cell, extent_x = (t.nx - 1) * c, extent_z = (t.ny - 1) * c;
  // Clip the ray to the terrain's footprint, so the walk starts and ends on it.
  double t0 = 0, t1 = std::numeric_limits<double>::infinity();
  const double axes[2][3] = {{o.x, d.x, extent_x}, {o.z, d.z, extent_z}};
  for (const auto& axis : axes) {
    const double p = axis[0], v = axis[1], hi = axis[2];
    if (std::fabs(v) < 1e-300) {
      if (p < 0 || p > hi) return std::nullopt;
      continue;
    }
    double a = (0 - p) / v, b = (hi - p) / v;
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  if (!(t0 <= t1) || !std::isfinite(t1)) return std::nullopt;
  const Vec start{o.x + t0 * d.x, o.y + t0 * d.y, o.z + t0 * d.z};
  int i = std::min(static_cast<int>(start.x / c), t.nx - 2),
      j = std::min(static_cast<int>(start.z / c), t.ny - 2);
  const int step_i = d.x > 0 ? 1 : -1, step_j = d.z > 0 ? 1 : -1;
  auto boundary = [&](double p, double v, int cell_index) {
    if (v > 0) return ((cell_index + 1) * c - p) / v;
    if (v < 0) return (cell_index * c - p) / v;
    return std::numeric_limits<double>::infinity();
  };
  double next_i = t0 + boundary(start.x, d.x, i), next_j = t0 + boundary(start.z, d.z, j);
  const double delta_i = d.x != 0 ? c / std::fabs(d.x) : std::numeric_limits<double>::infinity();
  const double delta_j = d.z != 0 ? c / std::fabs(d.z) : std::numeric_limits<double>::infinity();
  auto vertex = [&](int a, int b) { return Vec{a * c, static_cast<double>(t.at(a, b)), b * c}; };
  while (i >= 0 && j >= 0 && i < t.nx - 1 && j < t.ny - 1) {
    const Vec p00 = vertex(i, j), p10 = vertex(i + 1, j), p11 = vertex(i + 1, j + 1),
              p01 = vertex(i, j + 1);
    double best = -1;
    for (double hit :
         {moller_trumbore(o, d, p00, p10, p11), moller_trumbore(o, d, p00, p11, p01)}) {
      if (hit >= 0 && (best < 0 || hit < best)) best = hit;
    }
    if (best >= 0) return RayHit{best, o.x + best * d.x, o.y + best * d.y, o.z + best * d.z};
    if (std::min(next_i, next_j) > t1) break;
    if (next_i < next_j) {
      i += step_i;
      next_i += delta_i;
    } else {
      j += step_j;
      next_j += delta_j;
    }
  }
  return std::nullopt;
}

}  // namespace runnel
