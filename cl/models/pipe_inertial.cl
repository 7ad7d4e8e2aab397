// SPDX-License-Identifier: MIT
// The pipe model's flux under pipe.flux = "local-inertial" (docs/models.md, "pipe"): the inertial
// shallow-water flux of Bates, Horritt & Fewtrell (2010) with de Almeida et al.'s (2012) form,
// in place of Mei's pipes. Each face carries one signed flux Q (m³/s), stored as the two cells'
// outflows (Q⁺ in the cell it leaves, nothing in the other), and
//   Q ← (Q + g h Δt (η_k − η_m)) / (1 + g n² Δt |Q| / (l h^(7/3))),   h = max(η_k, η_m) − max(b_k, b_m),
// the water's own depth over the face, so waves travel at sqrt(g h), and a reversing flow is one
// flux turning, not two pipes, one slowing and one speeding. Both cells of a face compute the same
// Q bit for bit (negation and subtraction are exact), each keeps its own outflow. The same limit K
// as pipe_flux keeps a cell from sending more than it holds. The neighbours' outflows are read from
// the step's copy of the fluxes (old_flux), since every cell writes its own. Built after pipe.cl.

inline float inertial_face(float q_out, float q_in, float level, float bed, float other_level, float other_bed,
                           float dt, float cell) {
  const float q = q_out - q_in;  // signed, positive leaving this cell
  const float h = fmax(level, other_level) - fmax(bed, other_bed);
  if (!(h > 1e-6f)) return 0.0f;
  const float driven = q + PIPE_GRAVITY * h * dt * (level - other_level);
#if PIPE_FRICTION_ON
  const float third = pipe_inverse_cbrt(h);  // h^(−1/3): h^(−7/3) = third^7
  const float t2 = third * third, t4 = t2 * t2;
  return fmax(0.0f, driven / (1.0f + PIPE_GRAVITY_N2 * dt * fabs(q) / cell * (t4 * t2 * third)));
#else
  return fmax(0.0f, driven);
#endif
}

__kernel void pipe_flux_inertial(const __global float* height_view, const __global float* depth,
                                 const __global float* old_flux, __global float* flux,
                                 const int nx, const int ny, const float cell, const float dt,
                                 const __global float* rain_weight, const float rain_on) {
  const int k = get_global_id(0), n = nx * ny;
  if (k >= n) return;
  const int j = grid_row(k, nx), i = k - j * nx;
  const float b = height_view[k];
  const float d1 = depth[k] + dt * (PIPE_RAIN * rain_on * RAIN_WEIGHT(rain_weight, k));
  const float level = b + d1;
  // A face to the outside: closed, or a dry cell on the same bed beyond the edge (free outflow).
  float f[4];
  const int inside[4] = {i > 0, i < nx - 1, j > 0, j < ny - 1};
  const int other[4] = {k - 1, k + 1, k - nx, k + nx};
  for (int d = 0; d < 4; ++d) {
    if (!inside[d]) {
      f[d] = PIPE_CLOSED ? 0.0f : inertial_face(old_flux[d * n + k], 0.0f, level, b, b, b, dt, cell);
      continue;
    }
    const int m = other[d];
    const float other_level = pipe_level(height_view, depth, rain_weight, m, dt, rain_on);
    f[d] = inertial_face(old_flux[d * n + k], old_flux[(d ^ 1) * n + m], level, b, other_level, height_view[m], dt,
                         cell);
  }
  const float total = f[0] + f[1] + f[2] + f[3];
  const float scale = total > 0.0f ? fmin(1.0f, d1 * cell * cell / (total * dt)) : 0.0f;
  for (int d = 0; d < 4; ++d) flux[d * n + k] = f[d] * scale;
}
