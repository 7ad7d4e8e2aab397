// SPDX-License-Identifier: MIT
#include "runnel/terrain/surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "runnel/terrain/terrain_normals.hpp"

namespace runnel {

namespace {

// The triangle holding (x, z) and the barycentric weights of its vertices, the fourth vertex of
// the tile weighted 0: tiles split along (i, j)–(i+1, j+1) as cl/terrain_sample.cl splits them.
struct TileWeights {
  std::size_t k[4];  // (i, j), (i+1, j), (i, j+1), (i+1, j+1)
  double w[4];
};

TileWeights tile_weights(const Heightmap& t, double x, double z) {
  const double u = std::clamp(x / t.cell, 0.0, t.nx - 1.0),
               v = std::clamp(z / t.cell, 0.0, t.ny - 1.0);
  const int i = std::min(static_cast<int>(u), t.nx - 2),
            j = std::min(static_cast<int>(v), t.ny - 2);
  const double fx = u - i, fz = v - j;
  TileWeights tw;
  tw.k[0] = static_cast<std::size_t>(j) * t.nx + i;
  tw.k[1] = tw.k[0] + 1;
  tw.k[2] = tw.k[0] + t.nx;
  tw.k[3] = tw.k[2] + 1;
  if (fx >= fz) {
    tw.w[0] = 1 - fx, tw.w[1] = fx - fz, tw.w[3] = fz, tw.w[2] = 0;
  } else {
    tw.w[0] = 1 - fz, tw.w[2] = fz - fx, tw.w[3] = fx, tw.w[1] = 0;
  }
  return tw;
}

struct Vec3 {
  double x, y, z;
};
Vec3 operator-(Vec3 a, Vec3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
Vec3 operator+(Vec3 a, Vec3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
Vec3 operator*(double s, Vec3 a) {
  return {s * a.x, s * a.y, s * a.z};
}
double dot(Vec3 a, Vec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

// The point of triangle abc closest to p, by the Voronoi regions of its vertices, edges and face
// (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3 closest_point_on_triangle(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = 1 / (va + vb + vc);
  return a + (vb * denom) * ab + (vc * denom) * ac;
}

}  // namespace

double surface_height(const Heightmap& t, double x, double z) {
  const TileWeights tw = tile_weights(t, x, z);
  double height = 0;
  for (int v = 0; v < 4; ++v) height += tw.w[v] * t.h[tw.k[v]];
  return height;
}

SurfacePointReference surface_point(const Heightmap& t, const std::vector<float>& normals, double x,
                                    double z) {
  const TileWeights tw = tile_weights(t, x, z);
  SurfacePointReference s;
  s.height = 0;
  double normal[3] = {0, 0, 0};
  for (int v = 0; v < 4; ++v) {
    s.height += tw.w[v] * t.h[tw.k[v]];
    for (int a = 0; a < 3; ++a) normal[a] += tw.w[v] * normals[3 * tw.k[v] + a];
  }
  const double length =
      std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  for (int a = 0; a < 3; ++a) s.normal[a] = normal[a] / length;
  return s;
}

double wet_surface_height(const Heightmap& t, const std::vector<float>& depth, double x, double z) {
  const TileWeights tw = tile_weights(t, x, z);
  double surface = 0, weight = 0;
  for (int v = 0; v < 4; ++v)
    if (depth[tw.k[v]] > 0 && tw.w[v] > 0) {
      surface += tw.w[v] * (static_cast<double>(t.h[tw.k[v]]) + depth[tw.k[v]]);
      weight += tw.w[v];
    }
  return weight > 0 ? surface / weight : -std::numeric_limits<double>::infinity();
}

double distance_to_surface(const Heightmap& t, double x, double y, double z, double reach) {
  const Vec3 p{x, y, z};
  const auto vertex = [&](int i, int j) {
    return Vec3{i * t.cell, static_cast<double>(t.at(i, j)), j * t.cell};
  };
  const int i0 = std::max(0, static_cast<int>(std::floor((x - reach) / t.cell))),
            i1 = std::min(t.nx - 2, static_cast<int>(std::floor((x + reach) / t.cell))),
            j0 = std::max(0, static_cast<int>(std::floor((z - reach) / t.cell))),
            j1 = std::min(t.ny - 2, static_cast<int>(std::floor((z + reach) / t.cell)));
  double nearest = reach * reach;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const Vec3 a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1),
                 d = vertex(i, j + 1);
      for (const Vec3 q :
           {closest_point_on_triangle(p, a, b, c), closest_point_on_triangle(p, a, c, d)}) {
        const Vec3 gap = p - q;
        nearest = std::min(nearest, dot(gap, gap));
      }
    }
  return std::sqrt(nearest);
}

Heightmap contact_surface(const Heightmap& t, double radius) {
  Heightmap c = t;
  const std::vector<float> n = terrain_normals_reference(t);
  for (std::size_t k = 0; k < c.size(); ++k)
    c.h[k] += static_cast<float>(radius / std::max(0.2, static_cast<double>(n[3 * k + 1])));
  return c;
}

}  // namespace runnel
