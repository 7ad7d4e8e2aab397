// SPDX-License-Identifier: MIT
// Vertex normals of the heightmap (physics.md §1), central differences, one-sided at the border:
//   n = normalize(-dh/dx, 1, -dh/dz)
// height: m, nx × ny vertices, row-major (i fastest); normal: 3 floats per vertex.

__kernel void terrain_normals(const __global float* height, __global float* normal, const int nx,
                              const int ny, const float cell) {
  const int k = get_global_id(0);
  if (k >= nx * ny) return;
  const int j = grid_row(k, nx), i = k - j * nx;
  const int i0 = max(i - 1, 0), i1 = min(i + 1, nx - 1);
  const int j0 = max(j - 1, 0), j1 = min(j + 1, ny - 1);
  const float dhdx = (height[grid_index(i1, j, nx)] - height[grid_index(i0, j, nx)]) / ((float)(i1 - i0) * cell);
  const float dhdz = (height[grid_index(i, j1, nx)] - height[grid_index(i, j0, nx)]) / ((float)(j1 - j0) * cell);
  const float3 n = normalize((float3)(-dhdx, 1.0f, -dhdz));
  vstore3(n, k, normal);
}

