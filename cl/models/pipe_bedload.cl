// SPDX-License-Identifier: MIT
// The pipe model's bed-load law (pipe.law = "bedload"; docs/models.md, "pipe"): Wong & Parker's
// (2006) Meyer-Peter & Müller, q* = 3.97 (θ − θc)^(3/2), from the Shields stress of the Manning
// bed shear the pipe flow already feels; the bed follows Exner, (1 − p) ∂z/∂t = −∇·q. Each cell
// sends its load downstream through the faces its velocity points at, q_x and q_z of the vector
// q = |q| v / |v| (donor cell), in whole quanta by stochastic rounding with one u per cell and
// step; pipe_receive moves them and pipe_edge_outflow books what leaves the map, so the bed, the
// outflow and nothing else balance exactly. Built after pipe.cl (PIPE_* defines, pipe_inverse_cbrt)
// with the SED_* defines of SedimentSettings.

__kernel void pipe_bedload(const __global float* depth, const __global float* velocity, __global int* sent,
                           const int nx, const int ny, const float cell, const float dt, const float quantum,
                           const ulong key, const __global float* rock_erodibility,
                           const __global float* sediment_erodibility, const __global long* ground_sediment,
                           volatile __global long* moved) {
  const int k = get_global_id(0), n = nx * ny;
  if (k >= n) return;
  const int j = grid_row(k, nx), i = k - j * nx;
  const float d = depth[k], vx = velocity[k], vz = velocity[n + k];
  const float speed = sqrt(vx * vx + vz * vz);
  float quanta = 0.0f;  // bed quanta (grains and pores) the cell's load moves this step
  // Water thinner than pipe.cfl_depth moves no grains: a film's flux over its depth is no speed of
  // water over the bed (the same films the time step does not follow).
  if (d > PIPE_CFL_DEPTH && speed > 0.0f) {
    const float third = pipe_inverse_cbrt(d);  // d^(−1/3)
    const float tau = 1000.0f * PIPE_GRAVITY_N2 * speed * speed * third;  // Pa
    const float shields = tau / ((SED_GRAIN_DENSITY - 1000.0f) * PIPE_GRAVITY * SED_GRAIN_DIAMETER);
    const float excess = shields - SED_CRITICAL_SHIELDS;
    if (excess > 0.0f) {
      // q = q* sqrt(R g D³) = q* sqrt(R D g) D, m² of grains per s.
      const float q = SED_WONG_PARKER * excess * sqrt(excess) * sqrt(SED_SUBMERGED_RD * PIPE_GRAVITY) *
                      SED_GRAIN_DIAMETER;
      // q·l·dt of grains is q·l·dt / (1 − p) of bed, in quanta of quantum·l².
      quanta = fmin(BED_DETACHMENT(q * dt / ((1.0f - SED_POROSITY) * cell * quantum), k), 1.0e9f);
    }
  }
  const float ax = quanta * fabs(vx) / fmax(speed, 1e-30f), az = quanta * fabs(vz) / fmax(speed, 1e-30f);
  const float u = keyed_uniform(key, (uint)k);
  const int to_x = (int)(ax + u) - (int)u, to_z = (int)(ax + az + u) - (int)(ax + u);
  // Planes L R T B (pipe_send's); a closed edge lets nothing out.
  const int right = vx > 0.0f, down = vz > 0.0f;
  const int x_inside = right ? i < nx - 1 : i > 0, z_inside = down ? j < ny - 1 : j > 0;
  const int sx = PIPE_CLOSED && !x_inside ? 0 : to_x, sz = PIPE_CLOSED && !z_inside ? 0 : to_z;
  sent[0 * n + k] = right ? 0 : sx;
  sent[1 * n + k] = right ? sx : 0;
  sent[2 * n + k] = down ? 0 : sz;
  sent[3 * n + k] = down ? sz : 0;
  if (sx + sz > 0) atom_add(moved, (long)(sx + sz));
}
