// SPDX-License-Identifier: MIT
// The heightmap as a triangle mesh (physics.md §1): each tile (i..i+1, j..j+1) is split along the
// diagonal from (i, j) to (i+1, j+1). Height and normal at a point (x, z) come from the triangle
// that contains it: the plane's height, and the vertex normals interpolated barycentrically.
//
// The contact surface is the same mesh with every vertex raised by r / n_y (r a particle's radius,
// n_y its vertex normal's vertical part): on a plane that is exactly r along the normal, so a
// particle resting on the contact surface touches the terrain with its lowest point. n_y is
// bounded below so a near-vertical cliff does not lift the contact surface without limit.

#define CONTACT_MIN_NY 0.2f

typedef struct {
  float height;  // m
  float3 normal; // unit, interpolated vertex normal
} SurfacePoint;

// Height of vertex k raised by `radius` along its normal (0: the terrain itself).
inline float offset_height(const __global float* height, const __global float* normal, int k, float radius) {
  return height[k] + radius / fmax(normal[3 * k + 1], CONTACT_MIN_NY);
}

// The surface `radius` above the terrain (0: the terrain) at (x, z), clamped to the heightmap.
inline SurfacePoint offset_surface(const __global float* height, const __global float* normal, int nx, int ny,
                                   float cell, float radius, float x, float z) {
  const float u = clamp(x / cell, 0.0f, (float)(nx - 1));
  const float v = clamp(z / cell, 0.0f, (float)(ny - 1));
  const int i = min((int)u, nx - 2);
  const int j = min((int)v, ny - 2);
  const float fx = u - (float)i;
  const float fz = v - (float)j;
  const int k00 = j * nx + i, k10 = k00 + 1, k01 = k00 + nx, k11 = k01 + 1;
  float w00, w10, w01, w11;
  if (fx >= fz) {  // triangle (i,j), (i+1,j), (i+1,j+1)
    w00 = 1.0f - fx;
    w10 = fx - fz;
    w11 = fz;
    w01 = 0.0f;
  } else {  // triangle (i,j), (i+1,j+1), (i,j+1)
    w00 = 1.0f - fz;
    w01 = fz - fx;
    w11 = fx;
    w10 = 0.0f;
  }
  SurfacePoint s;
  s.height = w00 * offset_height(height, normal, k00, radius) + w10 * offset_height(height, normal, k10, radius) +
             w01 * offset_height(height, normal, k01, radius) + w11 * offset_height(height, normal, k11, radius);
  s.normal = normalize(w00 * vload3(k00, normal) + w10 * vload3(k10, normal) + w01 * vload3(k01, normal) +
                       w11 * vload3(k11, normal));
  return s;
}

inline SurfacePoint terrain_surface(const __global float* height, const __global float* normal, int nx, int ny,
                                    float cell, float x, float z) {
  return offset_surface(height, normal, nx, ny, cell, 0.0f, x, z);
}
