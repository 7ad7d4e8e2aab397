// SPDX-License-Identifier: MIT
// The heightmap as a triangle mesh (physics.md §1): each tile (i..i+1, j..j+1) is split along the
// diagonal from (i, j) to (i+1, j+1). Height and normal at a point (x, z) come from the triangle
// that contains it: the plane's height, and the vertex normals interpolated barycentrically.
//
// The contact surface is the same mesh with every vertex raised by r / n_y (raised_height in
// common.cl): on a plane that is exactly r along the normal, so a particle resting on the contact
// surface touches the terrain with its lowest point.

typedef struct {
  float height;  // m
  float3 normal; // unit, interpolated vertex normal
} SurfacePoint;

// The triangle under (x, z), clamped to the heightmap: its vertices' indices and the point's
// barycentric weights (the fourth vertex of the tile weighs 0).
typedef struct {
  int k00, k10, k01, k11;
  float w00, w10, w01, w11;
} TilePoint;

inline TilePoint tile_point(int nx, int ny, float cell, float x, float z) {
  const float u = clamp(x / cell, 0.0f, (float)(nx - 1));
  const float v = clamp(z / cell, 0.0f, (float)(ny - 1));
  const int i = min((int)u, nx - 2);
  const int j = min((int)v, ny - 2);
  const float fx = u - (float)i;
  const float fz = v - (float)j;
  TilePoint t;
  t.k00 = j * nx + i;
  t.k10 = t.k00 + 1;
  t.k01 = t.k00 + nx;
  t.k11 = t.k01 + 1;
  if (fx >= fz) {  // triangle (i,j), (i+1,j), (i+1,j+1)
    t.w00 = 1.0f - fx;
    t.w10 = fx - fz;
    t.w11 = fz;
    t.w01 = 0.0f;
  } else {  // triangle (i,j), (i+1,j+1), (i,j+1)
    t.w00 = 1.0f - fz;
    t.w01 = fz - fx;
    t.w11 = fx;
    t.w10 = 0.0f;
  }
  return t;
}

inline float3 tile_point_normal(const __global float* normal, TilePoint t) {
  return normalize(t.w00 * vload3(t.k00, normal) + t.w10 * vload3(t.k10, normal) + t.w01 * vload3(t.k01, normal) +
                   t.w11 * vload3(t.k11, normal));
}

// Height of vertex k raised by `radius` along its normal (0: the terrain itself).
inline float offset_height(const __global float* height, const __global float* normal, int k, float radius) {
  return raised_height(height[k], normal[3 * k + 1], radius);
}

// The surface `radius` above the terrain (0: the terrain) at (x, z), clamped to the heightmap.
inline SurfacePoint offset_surface(const __global float* height, const __global float* normal, int nx, int ny,
                                   float cell, float radius, float x, float z) {
  const TilePoint t = tile_point(nx, ny, cell, x, z);
  SurfacePoint s;
  s.height = t.w00 * offset_height(height, normal, t.k00, radius) + t.w10 * offset_height(height, normal, t.k10, radius) +
             t.w01 * offset_height(height, normal, t.k01, radius) + t.w11 * offset_height(height, normal, t.k11, radius);
  s.normal = tile_point_normal(normal, t);
  return s;
}

// The same for a surface whose raised vertex heights are kept (`surface`: DeviceTerrain's contact
// heights): the same value, bit for bit, as offset_surface at their radius.
inline SurfacePoint kept_surface(const __global float* surface, const __global float* normal, int nx, int ny,
                                 float cell, float x, float z) {
  const TilePoint t = tile_point(nx, ny, cell, x, z);
  SurfacePoint s;
  s.height = t.w00 * surface[t.k00] + t.w10 * surface[t.k10] + t.w01 * surface[t.k01] + t.w11 * surface[t.k11];
  s.normal = tile_point_normal(normal, t);
  return s;
}

// The terrain itself: its heights are the surface kept at radius 0 (h + 0 / n_y is h, and a height,
// a fixed-point value's view, is never −0), so it reads them without offset_surface's divisions.
inline SurfacePoint terrain_surface(const __global float* height, const __global float* normal, int nx, int ny,
                                    float cell, float x, float z) {
  return kept_surface(height, normal, nx, ny, cell, x, z);
}
