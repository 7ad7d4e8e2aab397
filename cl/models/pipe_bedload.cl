// SPDX-License-Identifier: MIT
// The pipe model's bed-load law (pipe.law = "bedload"; docs/models.md, "pipe"): Wong & Parker's
// (2006) Meyer-Peter & Müller, q* = 3.97 (θ − θc)^(3/2), from the Shields stress of the Manning
// bed shear of the flow through each face; the bed follows Exner, (1 − p) ∂z/∂t = −∇·q. The load
// crosses a face in the direction of the face's water flux Q, at the face's speed Q / (l h), h the
// mean depth of its two cells, and leaves the cell the water leaves (upwind, on the faces where the
// water's fluxes live, so bed and flow see the same velocities), in whole quanta by stochastic
// rounding with one u per cell and step; pipe_receive moves them and pipe_edge_outflow books what
// leaves the map, so the bed, the outflow and nothing else balance exactly. Built after pipe.cl
// (PIPE_* defines, pipe_inverse_cbrt) with the SED_* defines of SedimentSettings.

// A step lowers the bed by at most this fraction of the water over it: the bed must change slowly
// beside the flow for the two to be stepped apart (an Exner stability limit; it binds only at
// fronts and in films).
#define PIPE_BEDLOAD_MOST_OF_DEPTH 0.1f

// The bed quanta a face's flux `q_out` (m³/s leaving, ≥ 0) over water `h` deep carries in a step.
inline float face_bed_load(float q_out, float h, float cell, float dt, float quantum) {
  if (!(q_out > 0.0f) || !(h > PIPE_CFL_DEPTH)) return 0.0f;
  const float u = q_out / (cell * h);
  const float tau = 1000.0f * PIPE_GRAVITY_N2 * u * u * pipe_inverse_cbrt(h);  // Pa
  const float shields = tau / ((SED_GRAIN_DENSITY - 1000.0f) * PIPE_GRAVITY * SED_GRAIN_DIAMETER);
  const float excess = shields - SED_CRITICAL_SHIELDS;
  if (!(excess > 0.0f)) return 0.0f;
  // q = q* sqrt(R g D³) = q* sqrt(R D g) D, m² of grains per s; q·l·Δt of grains is q·l·Δt / (1 − p)
  // of bed, in quanta of quantum·l².
  const float q = SED_WONG_PARKER * excess * sqrt(excess) * sqrt(SED_SUBMERGED_RD * PIPE_GRAVITY) * SED_GRAIN_DIAMETER;
  return q * dt / ((1.0f - SED_POROSITY) * cell * quantum);
}

__kernel void pipe_bedload(const __global float* depth, const __global float* flux, __global int* sent,
                           const int nx, const int ny, const float cell, const float dt, const float quantum,
                           const ulong key, const __global float* rock_erodibility,
                           const __global float* sediment_erodibility, const __global long* ground_sediment,
                           volatile __global long* moved) {
  const int k = get_global_id(0), n = nx * ny;
  if (k >= n) return;
  const int j = grid_row(k, nx), i = k - j * nx;
  const float d = depth[k];
  // Faces L R T B: the net flux leaving through each, over the mean depth of its two cells (this
  // cell's alone at the map's edge, where a closed edge carries no flux).
  const int inside[4] = {i > 0, i < nx - 1, j > 0, j < ny - 1};
  const int other[4] = {k - 1, k + 1, k - nx, k + nx};
  float load[4];
  float total = 0.0f;
  for (int f = 0; f < 4; ++f) {
    const int m = inside[f] ? other[f] : k;
    const float q_out = flux[f * n + k] - (inside[f] ? flux[(f ^ 1) * n + m] : 0.0f);
    const float h = inside[f] ? 0.5f * (d + depth[m]) : d;
    load[f] = PIPE_CLOSED && !inside[f] ? 0.0f : face_bed_load(q_out, h, cell, dt, quantum);
    total += load[f];
  }
  const float most = PIPE_BEDLOAD_MOST_OF_DEPTH * d / quantum;
  const float allowed = fmin(BED_DETACHMENT(fmin(total, most), k), 1.0e9f);
  const float scale = total > 0.0f ? allowed / total : 0.0f;
  // Systematic sampling: the faces' shares of the allowed load, cumulated, with one u.
  const float u = keyed_uniform(key, (uint)k);
  int before = (int)u, sum = 0;
  float cumulative = 0.0f;
  for (int f = 0; f < 4; ++f) {
    cumulative += load[f] * scale;
    const int at = (int)(cumulative + u);
    sent[f * n + k] = at - before;
    sum += at - before;
    before = at;
  }
  if (sum > 0) atom_add(moved, (long)sum);
}
