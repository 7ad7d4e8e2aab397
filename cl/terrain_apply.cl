// SPDX-License-Identifier: MIT
// Applies a step's height changes (physics.md §4, "Determinism"). Erosion, deposition and talus
// accumulate per-vertex changes as 64-bit integer counts of the height quantum q with integer
// atomics (their sum does not depend on order); here they are added to the fixed-point heights
// once per step, and the float heights the other kernels read are refreshed:
//   h_fixed += delta;  delta = 0;  height = h_fixed · q
// The float view is computed from the high and low bits separately, so it stays accurate to a
// float's rounding without double precision on the device.
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable

__kernel void terrain_apply(__global long* height_fixed, __global long* delta, __global float* height, const uint n,
                            const float quantum) {
  const uint k = get_global_id(0);
  if (k >= n) return;
  const long h = height_fixed[k] + delta[k];
  height_fixed[k] = h;
  delta[k] = 0;
  const long high = h >> 20;  // arithmetic shift: floor division by 2^20, also for negative heights
  const long low = h - (high << 20);
  height[k] = (float)high * (quantum * 1048576.0f) + (float)low * quantum;
}
