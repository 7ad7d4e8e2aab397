// SPDX-License-Identifier: MIT
// Vertex normals of the heightmap (physics.md §1), central differences, one-sided at the border:
//   n = normalize(-dh/dx, 1, -dh/dz)
// height: m, nx × ny vertices, row-major (i fastest); normal: 3 floats per vertex.

// Only the vertices of the tiles marked in `stale` are recomputed. With `carry_contact`, also the
// vertices of the contact surface `contact_radius` above the terrain (terrain_sample.cl), which the
// SPH drift samples several times a particle and step: kept here, they cost a load instead of a
// load, a division and the normal's load each (DeviceTerrain::carry_contact_surface).
__kernel void terrain_normals(const __global float* height, __global float* normal, const int nx,
                              const int ny, const float cell, const __global uint* stale, const int tiles_x,
                              const int carry_contact, const float contact_radius, __global float* contact) {
  const int k = get_global_id(0);
  if (k >= nx * ny) return;
  const int j = grid_row(k, nx), i = k - j * nx;
  if (!stale[terrain_tile(i, j, tiles_x)]) return;
  const int i0 = max(i - 1, 0), i1 = min(i + 1, nx - 1);
  const int j0 = max(j - 1, 0), j1 = min(j + 1, ny - 1);
  const float dhdx = (height[grid_index(i1, j, nx)] - height[grid_index(i0, j, nx)]) / ((float)(i1 - i0) * cell);
  const float dhdz = (height[grid_index(i, j1, nx)] - height[grid_index(i, j0, nx)]) / ((float)(j1 - j0) * cell);
  // Scalars, not float3 and normalize(): a vector value in a work-item stops PoCL's vectoriser.
  const float inverse_length = 1.0f / sqrt(dhdx * dhdx + 1.0f + dhdz * dhdz);
  normal[3 * k] = -dhdx * inverse_length;
  normal[3 * k + 1] = inverse_length;
  normal[3 * k + 2] = -dhdz * inverse_length;
  if (carry_contact) contact[k] = raised_height(height[k], inverse_length, contact_radius);
}

