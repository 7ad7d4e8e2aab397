// SPDX-License-Identifier: MIT
// Evaluates the SPH kernel functions of sph_kernel.cl at given distances, so tests can check them
// against the C++ reference and the analytic integrals.

__kernel void sph_kernel_probe(const __global float* r, const uint n, __global float* w, __global float* grad,
                               __global float* wall_g, __global float* wall_a, __global float* wall_b,
                               __global float* wall_v) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  w[i] = wendland_w(r[i]);
  grad[i] = wendland_grad_factor(r[i]);
  wall_g[i] = wall_integral(r[i]);
  wall_a[i] = wall_moment_normal(r[i]);
  wall_b[i] = wall_moment_tangent(r[i]);
  wall_v[i] = wall_volume(r[i]);
}
