// SPDX-License-Identifier: MIT
// The pipe model's water under pipe.flux = "godunov" (docs/models.md, "pipe"): the shallow-water
// equations in finite volumes, first order, the HLL Riemann solver at each face (Harten, Lax & van
// Leer 1983, Davis's wave speeds, Toro's dry-bed speeds) on the hydrostatic reconstruction of
// Audusse et al. (2004), which keeps a lake at rest and the water depths non-negative over any bed.
// The state is the depth d and the velocity (u, v) of each cell; advection is in the fluxes, so a
// dam break's jet runs supercritical. Two passes a step:
//   pipe_godunov_faces:  each cell's right (x) and lower (z) face: reconstructed states, the HLL flux
//                        (mass, x- and z-momentum per metre of face) into face_flux;
//   pipe_godunov_update: each cell from its four faces' fluxes and the reconstruction's pressure
//                        corrections; Manning friction implicitly; the faces' water outflows
//                        (m³/s) into the pipes' flux planes, which the sediment transport and the bed
//                        load read as they read Mei's pipes; then what pipe_water leaves for the
//                        erosion stages (previous depth, capacity, CFL speeds).
// Edges: closed, a mirror cell (reflecting); outflow, a free overfall: beyond the edge the ground
// falls away and is dry, so the water leaves at critical depth or faster and nothing comes back in
// (a copy of the cell, the usual transmissive edge, keeps a sheet's momentum but not the bed's
// slope: the last cell lost half its push and water piled up there).
// Built after pipe.cl (PIPE_* defines, pipe_capacity, pipe_inverse_cbrt).

#define GODUNOV_DRY 1e-6f  // m: thinner water has no velocity

// The HLL flux across a face with normal velocity un and tangential ut on each side, for depths
// hl, hr already reconstructed: mass, normal momentum, tangential momentum.
inline float3 hll_flux(float hl, float unl, float utl, float hr, float unr, float utr) {
  if (hl <= GODUNOV_DRY && hr <= GODUNOV_DRY) return (float3)(0.0f);
  const float g = PIPE_GRAVITY, cl = sqrt(g * hl), cr = sqrt(g * hr);
  float sl, sr;
  if (hl <= GODUNOV_DRY) {
    sl = unr - 2.0f * cr, sr = unr + cr;
  } else if (hr <= GODUNOV_DRY) {
    sl = unl - cl, sr = unl + 2.0f * cl;
  } else {
    sl = fmin(unl - cl, unr - cr), sr = fmax(unl + cl, unr + cr);
  }
  const float3 fl = (float3)(hl * unl, hl * unl * unl + 0.5f * g * hl * hl, hl * unl * utl);
  const float3 fr = (float3)(hr * unr, hr * unr * unr + 0.5f * g * hr * hr, hr * unr * utr);
  if (sl >= 0.0f) return fl;
  if (sr <= 0.0f) return fr;
  const float3 ul = (float3)(hl, hl * unl, hl * utl), ur = (float3)(hr, hr * unr, hr * utr);
  return (sr * fl - sl * fr + sl * sr * (ur - ul)) / (sr - sl);
}

// The flux across the face between cells a (left or upper) and b, from their beds, depths and
// velocities (normal, tangential), on Audusse's reconstruction.
inline float3 reconstructed_flux(float za, float ha, float una, float uta, float zb, float hb, float unb, float utb) {
  const float z = fmax(za, zb);
  return hll_flux(fmax(0.0f, ha + za - z), una, uta, fmax(0.0f, hb + zb - z), unb, utb);
}

// The flux through the map's edge after a cell (its right or lower face), for its depth and its
// normal and tangential velocities: against a mirror (closed) or a dry, lower ground (outflow).
inline float3 edge_flux_after(float h, float un, float ut) {
#if PIPE_CLOSED
  return hll_flux(h, un, ut, h, -un, ut);
#else
  return hll_flux(h, un, ut, 0.0f, 0.0f, 0.0f);
#endif
}

// The same before a cell (its left or upper face), which no cell owns.
inline float3 edge_flux_before(float h, float un, float ut) {
#if PIPE_CLOSED
  return hll_flux(h, -un, ut, h, un, ut);
#else
  return hll_flux(0.0f, 0.0f, 0.0f, h, un, ut);
#endif
}

__kernel void pipe_godunov_faces(const __global float* height_view, const __global float* depth,
                                 const __global float* velocity, __global float* face_flux, const int nx,
                                 const int ny, const float dt, const __global float* rain_weight,
                                 const float rain_on) {
  const int k = get_global_id(0), n = nx * ny;
  if (k >= n) return;
  const int j = grid_row(k, nx), i = k - j * nx;
  const float rain = dt * PIPE_RAIN * rain_on;
  const float z = height_view[k], h = depth[k] + rain * RAIN_WEIGHT(rain_weight, k);
  const float u = velocity[k], v = velocity[n + k];
  // Right face (x): the neighbour, or beyond the edge a mirror (closed) or a copy (outflow).
  float3 fx;
  if (i < nx - 1) {
    const int m = k + 1;
    fx = reconstructed_flux(z, h, u, v, height_view[m], depth[m] + rain * RAIN_WEIGHT(rain_weight, m), velocity[m],
                   velocity[n + m]);
  } else {
    fx = edge_flux_after(h, u, v);
  }
  // Lower face (z): normal velocity v, tangential u.
  float3 fz;
  if (j < ny - 1) {
    const int m = k + nx;
    fz = reconstructed_flux(z, h, v, u, height_view[m], depth[m] + rain * RAIN_WEIGHT(rain_weight, m), velocity[n + m],
                   velocity[m]);
  } else {
    fz = edge_flux_after(h, v, u);
  }
  face_flux[0 * n + k] = fx.x, face_flux[1 * n + k] = fx.y, face_flux[2 * n + k] = fx.z;
  face_flux[3 * n + k] = fz.x, face_flux[4 * n + k] = fz.y, face_flux[5 * n + k] = fz.z;
}

__kernel void pipe_godunov_update(__global float* depth, __global float* velocity, __global float* flux,
                                  const __global float* face_flux, __global float* previous_depth,
                                  const __global float* height_view, __global float* capacity, const int nx,
                                  const int ny, const float cell, const float dt, const __global float* rain_weight,
                                  const float rain_on, const float evaporation_factor, __global float* cfl_speed2) {
  const int k = get_global_id(0), n = nx * ny;
  if (k >= n) return;
  const int j = grid_row(k, nx), i = k - j * nx;
  const float g = PIPE_GRAVITY, rain = dt * PIPE_RAIN * rain_on;
  const float z = height_view[k], h = depth[k] + rain * RAIN_WEIGHT(rain_weight, k);
  const float u = velocity[k], v = velocity[n + k];
  // The four faces' fluxes, oriented along +x and +z.
  const float3 right = (float3)(face_flux[0 * n + k], face_flux[1 * n + k], face_flux[2 * n + k]);
  const float3 lower = (float3)(face_flux[3 * n + k], face_flux[4 * n + k], face_flux[5 * n + k]);
  const float3 left = i > 0 ? (float3)(face_flux[0 * n + k - 1], face_flux[1 * n + k - 1],
                                       face_flux[2 * n + k - 1])
                            : edge_flux_before(h, u, v);
  const float3 upper = j > 0 ? (float3)(face_flux[3 * n + k - nx], face_flux[4 * n + k - nx],
                                        face_flux[5 * n + k - nx])
                             : edge_flux_before(h, v, u);
  // Audusse's pressure corrections: each face's momentum flux as this cell sees it, with the
  // hydrostatic pressure of its own depth against the reconstructed one.
  float zr = z, zl = z, zu = z, zd = z;
  if (i < nx - 1) zr = height_view[k + 1];
  if (i > 0) zl = height_view[k - 1];
  if (j > 0) zu = height_view[k - nx];
  if (j < ny - 1) zd = height_view[k + nx];
  const float hr = fmax(0.0f, h + z - fmax(z, zr)), hl = fmax(0.0f, h + z - fmax(z, zl));
  const float hu_ = fmax(0.0f, h + z - fmax(z, zu)), hd = fmax(0.0f, h + z - fmax(z, zd));
  const float half_g = 0.5f * g;
  const float s = dt / cell;
  const float h_new = fmax(0.0f, h - s * (right.x - left.x + lower.x - upper.x));
  float qx = h * u - s * ((right.y + half_g * (h * h - hr * hr)) - (left.y + half_g * (h * h - hl * hl)) +
                          lower.z - upper.z);
  float qz = h * v - s * ((lower.y + half_g * (h * h - hd * hd)) - (upper.y + half_g * (h * h - hu_ * hu_)) +
                          right.z - left.z);
  float un = 0.0f, vn = 0.0f;
  if (h_new > GODUNOV_DRY) {
    un = qx / h_new, vn = qz / h_new;
#if PIPE_FRICTION_ON
    // Manning's friction, implicitly: u /= 1 + Δt g n² |u| / d^(4/3).
    const float third = pipe_inverse_cbrt(fmax(h_new, 1e-3f));
    const float speed = sqrt(un * un + vn * vn);
    const float damp = 1.0f + dt * PIPE_GRAVITY_N2 * speed * third * third * third * third;
    un /= damp, vn /= damp;
#endif
  }
  previous_depth[k] = h;
  const float d_evaporated = h_new * evaporation_factor;
  depth[k] = d_evaporated;
  velocity[k] = un;
  velocity[n + k] = vn;
  // The water each face carried out of this cell (m³/s), for the sediment transport and the bed load.
  flux[0 * n + k] = fmax(-left.x, 0.0f) * cell;
  flux[1 * n + k] = fmax(right.x, 0.0f) * cell;
  flux[2 * n + k] = fmax(-upper.x, 0.0f) * cell;
  flux[3 * n + k] = fmax(lower.x, 0.0f) * cell;
  capacity[k] = pipe_capacity(height_view, nx, ny, i, j, k, cell, un, vn, h_new);
  const float v2 = un * un + vn * vn;
  cfl_speed2[k] = d_evaporated >= PIPE_CFL_DEPTH ? v2 : 0.0f * v2;  // NaN stays NaN
}
