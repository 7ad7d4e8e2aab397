// SPDX-License-Identifier: MIT
// Applies a step's height changes (physics.md §4, "Determinism"). Erosion, deposition and talus
// accumulate per-vertex changes as 64-bit integer counts of the height quantum q with integer
// atomics (their sum does not depend on order); here they are added to the fixed-point heights
// once per step, and the float heights the other kernels read are refreshed:
//   h_fixed += delta;  delta = 0;  height = h_fixed · q
// The float view is computed from the high and low bits separately, so it stays accurate to a
// float's rounding without double precision on the device. Only the tiles marked in `changed` can
// hold deltas (the kernels that add them mark their tiles); the others are left as they are.
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable

__kernel void terrain_apply(__global long* height_fixed, __global long* delta, __global float* height, const int nx,
                            const int ny, const float quantum, const __global uint* changed, const int tiles_x) {
  const int k = get_global_id(0);
  if (k >= nx * ny) return;
  const int j = grid_row(k, nx), i = k - j * nx;
  if (!changed[terrain_tile(i, j, tiles_x)]) return;
  const long h = height_fixed[k] + delta[k];
  height_fixed[k] = h;
  delta[k] = 0;
  height[k] = fixed_height_view(h, quantum);
}

// The view alone, for a terrain whose models write height_fixed directly and never add deltas (the
// grid models): a third of terrain_apply's memory traffic.
__kernel void terrain_view(const __global long* height_fixed, __global float* height, const int n,
                           const float quantum) {
  const int k = get_global_id(0);
  if (k >= n) return;
  height[k] = fixed_height_view(height_fixed[k], quantum);
}

// The view of the tiles marked in `changed`, for a step whose kernels added their changes straight to
// height_fixed (DeviceTerrain::bind_fixed_changes): they read only the float view during the step,
// so the fixed heights need no separate deltas, and the pass moves 12 bytes a vertex instead of 28.
__kernel void terrain_view_changed(const __global long* height_fixed, __global float* height, const int nx,
                                   const int ny, const float quantum, const __global uint* changed,
                                   const int tiles_x) {
  const int k = get_global_id(0);
  if (k >= nx * ny) return;
  const int j = grid_row(k, nx), i = k - j * nx;
  if (!changed[terrain_tile(i, j, tiles_x)]) return;
  height[k] = fixed_height_view(height_fixed[k], quantum);
}

// The tiles whose normals a step's changes made stale: the changed tiles and their neighbours (a
// vertex's normal reads the heights one vertex away, which may lie in the next tile).
__kernel void terrain_stale_normals(const __global uint* changed, __global uint* stale, const int tiles_x,
                                    const int tiles_y) {
  const int t = get_global_id(0);
  if (t >= tiles_x * tiles_y) return;
  const int tj = t / tiles_x, ti = t - tj * tiles_x;
  uint any = 0;
  for (int b = max(tj - 1, 0); b <= min(tj + 1, tiles_y - 1); ++b)
    for (int a = max(ti - 1, 0); a <= min(ti + 1, tiles_x - 1); ++a) any |= changed[b * tiles_x + a];
  if (any) stale[t] = 1u;
}
