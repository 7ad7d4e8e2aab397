// SPDX-License-Identifier: MIT
// The pipe model's water under pipe.flux = "godunov" (docs/models.md, "pipe"): the shallow-water
// equations in finite volumes, first order, the HLL Riemann solver at each face (Harten, Lax & van
// Leer 1983, Davis's wave speeds, Toro's dry-bed speeds) on the hydrostatic reconstruction of
// Audusse et al. (2004), which keeps a lake at rest and the water depths non-negative over any bed.
// The bed is reconstructed as a line in each cell (the minmod of its one-sided differences), the
// depth's limited slope held to the bed's size, the velocity constant; the bed's slope enters as
// Audusse's centred source −g h Δz over the cell. With the bed as a step in each cell (the
// reconstruction alone) the faces see a sheet on a slope fall from step to step and it loses
// g Δz² / 2 of each step's push (S l / 2h of it: +8 % depth on 0.1 m cells of a 20 % plane).
// A lake's surface stays flat (its depth's slope is exactly the bed's opposite), and the depths at
// the faces stay between the neighbours', so non-negative.
// The state is the depth d and the velocity (u, v) of each cell; advection is in the fluxes, so a
// dam break's jet runs supercritical. Three passes a step:
//   pipe_godunov_slopes: each cell's limited bed and depth slopes along x and z into slopes;
//   pipe_godunov_faces:  each cell's right (x) and lower (z) face: reconstructed states, the HLL flux
//                        (mass, normal momentum as each side sees it with its pressure correction,
//                        tangential momentum, per metre of face) into face_flux;
//   pipe_godunov_update: each cell from its four faces' fluxes (with the reconstruction's pressure
//                        corrections) and its bed's centred source; Manning friction implicitly; the faces' water outflows
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

// The limited slopes of the bed z and the depth h across cell k along a stride (1: x, nx: z), as
// their change over one cell. Each is the minmod of its two one-sided differences, and the depth's
// is held to the bed's size: where the bed is flat the depth stays constant in the cell (first order:
// a linear depth with forward Euler steps turned Ritter's thinning tip into a bore), on a lake it is
// exactly the bed's opposite (the surface flat: at rest). 0 at the map's edges and wherever a
// neighbour is dry (first order at fronts).
inline float minmod(float before, float after) {
  const float smaller = copysign(fmin(fabs(before), fabs(after)), before);
  return before * after > 0.0f ? smaller : 0.0f;
}
inline float2 bed_and_depth_slopes(const __global float* height_view, const __global float* depth,
                                   const __global float* rain_weight, float rain, int k, int stride, int n,
                                   int has_both) {
  const int a = max(k - stride, 0), b = min(k + stride, n - 1);
  const float ha = depth[a] + rain * RAIN_WEIGHT(rain_weight, a), hk = depth[k] + rain * RAIN_WEIGHT(rain_weight, k),
              hb = depth[b] + rain * RAIN_WEIGHT(rain_weight, b);
  const float za = height_view[a], zk = height_view[k], zb = height_view[b];
  // First order at the map's edges and wherever a neighbour is dry.
  const float full = has_both && fmin(ha, fmin(hk, hb)) > GODUNOV_DRY ? 1.0f : 0.0f;
  const float bed = full * minmod(zk - za, zb - zk), dh = minmod(hk - ha, hb - hk);
  return (float2)(bed, copysign(fmin(fabs(dh), fabs(bed)), dh));
}

// A face between cells a (left or upper) and b: the mass flux, the normal momentum flux as a and as
// b see it (Audusse's correction g/2 (h² − h*²) of each side's own depth at the face against the
// reconstructed one), the tangential momentum flux.
typedef struct {
  float mass, momentum_a, momentum_b, tangential;
} GodunovFace;

// The face from each side's bed and depth at the face, and its velocities (normal, tangential),
// on Audusse's reconstruction.
inline GodunovFace reconstructed_face(float za, float ha, float una, float uta, float zb, float hb, float unb,
                                      float utb) {
  const float z = fmax(za, zb);
  const float ha_star = fmax(0.0f, ha + za - z), hb_star = fmax(0.0f, hb + zb - z);
  const float3 f = hll_flux(ha_star, una, uta, hb_star, unb, utb);
  const float half_g = 0.5f * PIPE_GRAVITY;
  GodunovFace face;
  face.mass = f.x;
  face.momentum_a = f.y + half_g * (ha * ha - ha_star * ha_star);
  face.momentum_b = f.y + half_g * (hb * hb - hb_star * hb_star);
  face.tangential = f.z;
  return face;
}

// A face without a reconstruction (the map's edges): both sides see the same flux.
inline GodunovFace face_of(float3 f) {
  GodunovFace face;
  face.mass = f.x, face.momentum_a = f.y, face.momentum_b = f.y, face.tangential = f.z;
  return face;
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

__kernel void pipe_godunov_slopes(const __global float* height_view, const __global float* depth,
                                  __global float* slopes, const int nx, const int ny, const float dt,
                                  const __global float* rain_weight, const float rain_on) {
  const int k = get_global_id(0), n = nx * ny;
  if (k >= n) return;
  const int j = grid_row(k, nx), i = k - j * nx;
  const float rain = dt * PIPE_RAIN * rain_on;
  const float2 sx = bed_and_depth_slopes(height_view, depth, rain_weight, rain, k, 1, n, i > 0 && i < nx - 1);
  const float2 sz = bed_and_depth_slopes(height_view, depth, rain_weight, rain, k, nx, n, j > 0 && j < ny - 1);
  slopes[0 * n + k] = sx.x, slopes[1 * n + k] = sx.y, slopes[2 * n + k] = sz.x, slopes[3 * n + k] = sz.y;
}

__kernel void pipe_godunov_faces(const __global float* height_view, const __global float* depth,
                                 const __global float* velocity, const __global float* slopes,
                                 __global float* face_flux, const int nx,
                                 const int ny, const float dt, const __global float* rain_weight,
                                 const float rain_on) {
  const int k = get_global_id(0), n = nx * ny;
  if (k >= n) return;
  const int j = grid_row(k, nx), i = k - j * nx;
  const float rain = dt * PIPE_RAIN * rain_on;
  const float z = height_view[k], h = depth[k] + rain * RAIN_WEIGHT(rain_weight, k);
  const float u = velocity[k], v = velocity[n + k];
  const float2 sx = (float2)(slopes[0 * n + k], slopes[1 * n + k]);
  const float2 sz = (float2)(slopes[2 * n + k], slopes[3 * n + k]);
  // Right face (x): the neighbour, or beyond the edge a mirror (closed) or dry ground (outflow).
  GodunovFace fx;
  if (i < nx - 1) {
    const int m = k + 1;
    const float2 sm = (float2)(slopes[0 * n + m], slopes[1 * n + m]);
    fx = reconstructed_face(z + 0.5f * sx.x, h + 0.5f * sx.y, u, v, height_view[m] - 0.5f * sm.x,
                            depth[m] + rain * RAIN_WEIGHT(rain_weight, m) - 0.5f * sm.y, velocity[m], velocity[n + m]);
  } else {
    fx = face_of(edge_flux_after(h, u, v));
  }
  // Lower face (z): normal velocity v, tangential u.
  GodunovFace fz;
  if (j < ny - 1) {
    const int m = k + nx;
    const float2 sm = (float2)(slopes[2 * n + m], slopes[3 * n + m]);
    fz = reconstructed_face(z + 0.5f * sz.x, h + 0.5f * sz.y, v, u, height_view[m] - 0.5f * sm.x,
                            depth[m] + rain * RAIN_WEIGHT(rain_weight, m) - 0.5f * sm.y, velocity[n + m], velocity[m]);
  } else {
    fz = face_of(edge_flux_after(h, v, u));
  }
  face_flux[0 * n + k] = fx.mass, face_flux[1 * n + k] = fx.momentum_a, face_flux[2 * n + k] = fx.momentum_b;
  face_flux[3 * n + k] = fx.tangential;
  face_flux[4 * n + k] = fz.mass, face_flux[5 * n + k] = fz.momentum_a, face_flux[6 * n + k] = fz.momentum_b;
  face_flux[7 * n + k] = fz.tangential;
}

__kernel void pipe_godunov_update(__global float* depth, __global float* velocity, __global float* flux,
                                  const __global float* face_flux, const __global float* slopes,
                                  __global float* previous_depth,
                                  const __global float* height_view, __global float* capacity, const int nx,
                                  const int ny, const float cell, const float dt, const __global float* rain_weight,
                                  const float rain_on, const float evaporation_factor, __global float* cfl_speed2) {
  const int k = get_global_id(0), n = nx * ny;
  if (k >= n) return;
  const int j = grid_row(k, nx), i = k - j * nx;
  const float g = PIPE_GRAVITY, rain = dt * PIPE_RAIN * rain_on;
  const float h = depth[k] + rain * RAIN_WEIGHT(rain_weight, k);
  const float u = velocity[k], v = velocity[n + k];
  // The four faces' fluxes, oriented along +x and +z, the normal momentum as this cell sees it.
  const GodunovFace right = {face_flux[0 * n + k], face_flux[1 * n + k], 0.0f, face_flux[3 * n + k]};
  const GodunovFace lower = {face_flux[4 * n + k], face_flux[5 * n + k], 0.0f, face_flux[7 * n + k]};
  const GodunovFace left =
      i > 0 ? (GodunovFace){face_flux[0 * n + k - 1], 0.0f, face_flux[2 * n + k - 1], face_flux[3 * n + k - 1]}
            : face_of(edge_flux_before(h, u, v));
  const GodunovFace upper = j > 0 ? (GodunovFace){face_flux[4 * n + k - nx], 0.0f, face_flux[6 * n + k - nx],
                                                  face_flux[7 * n + k - nx]}
                                  : face_of(edge_flux_before(h, v, u));
  const float s = dt / cell;
  const float h_new = fmax(0.0f, h - s * (right.mass - left.mass + lower.mass - upper.mass));
  // The momentum: the faces' fluxes and the bed's centred source g h Δz over the cell.
  float qx = h * u - s * (right.momentum_a - left.momentum_b + lower.tangential - upper.tangential +
                          g * h * slopes[0 * n + k]);
  float qz = h * v - s * (lower.momentum_a - upper.momentum_b + right.tangential - left.tangential +
                          g * h * slopes[2 * n + k]);
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
  flux[0 * n + k] = fmax(-left.mass, 0.0f) * cell;
  flux[1 * n + k] = fmax(right.mass, 0.0f) * cell;
  flux[2 * n + k] = fmax(-upper.mass, 0.0f) * cell;
  flux[3 * n + k] = fmax(lower.mass, 0.0f) * cell;
  capacity[k] = pipe_capacity(height_view, nx, ny, i, j, k, cell, un, vn, h_new);
  const float v2 = un * un + vn * vn;
  cfl_speed2[k] = d_evaporated >= PIPE_CFL_DEPTH ? v2 : 0.0f * v2;  // NaN stays NaN
}
