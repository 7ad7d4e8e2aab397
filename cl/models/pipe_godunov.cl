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
// dam break's jet runs supercritical. Four passes a step:
//   pipe_godunov_slopes: each cell's limited bed and depth slopes along x and z into slopes;
//   pipe_godunov_faces:  each cell's right (x) and lower (z) face: reconstructed states, the HLL flux
//                        (mass, normal momentum as each side sees it with its pressure correction,
//                        tangential momentum, per metre of face) into face_flux;
//   pipe_godunov_edges:  the faces on the map's edges;
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

// Written for PoCL's loop vectoriser, which runs the work-items of a group as the lanes of a loop:
// scalars only (it gives up on a loop with a float2 or float3 value in it), helpers always inlined
// (PoCL builds with -Dinline=, and a call stops it), no branch around a load (the edges' neighbours
// are read at a clamped index and their flux selected away), and no isomorphic pair of operations
// side by side where it can be helped, which the SLP vectoriser packs into a 2-wide vector first
// (the faces' two sides still are: that pass runs one cell at a time). A cell reads both the
// neighbour's flux and the edge's (pipe_godunov_edges computes those once) and keeps one.

// A face's flux: mass, normal momentum, tangential momentum (per metre of face).
typedef struct {
  float mass, momentum, tangential;
} HllFlux;

// The HLL flux across a face with normal velocity un and tangential ut on each side, for depths
// hl, hr already reconstructed. In float3 and with branches: only the faces' pass (which runs a cell
// at a time, see above; the SLP vectoriser packs the three components) and the edges' call it.
ALWAYS_INLINE HllFlux hll_flux(float hl, float unl, float utl, float hr, float unr, float utr) {
  HllFlux flux = {0.0f, 0.0f, 0.0f};
  if (hl <= GODUNOV_DRY && hr <= GODUNOV_DRY) return flux;
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
  float3 f;
  if (sl >= 0.0f) {
    f = fl;
  } else if (sr <= 0.0f) {
    f = fr;
  } else {
    const float3 ul = (float3)(hl, hl * unl, hl * utl), ur = (float3)(hr, hr * unr, hr * utr);
    f = (sr * fl - sl * fr + sl * sr * (ur - ul)) / (sr - sl);
  }
  flux.mass = f.x, flux.momentum = f.y, flux.tangential = f.z;
  return flux;
}

// The limited slopes of the bed z and the depth h across cell k along a stride (1: x, nx: z), as
// their change over one cell. Each is the minmod of its two one-sided differences, and the depth's
// is held to the bed's size: where the bed is flat the depth stays constant in the cell (first order:
// a linear depth with forward Euler steps turned Ritter's thinning tip into a bore), on a lake it is
// exactly the bed's opposite (the surface flat: at rest). 0 at the map's edges and wherever a
// neighbour is dry (first order at fronts).
// copysign(magnitude, sign) in bits: PoCL's copysign stops the loop vectoriser.
ALWAYS_INLINE float with_sign_of(float magnitude, float sign) {
  return as_float((as_uint(magnitude) & 0x7fffffffu) | (as_uint(sign) & 0x80000000u));
}
ALWAYS_INLINE float minmod(float before, float after) {
  // |after| as fmax(after, −after): the same two magnitudes as fabs, but not an isomorphic pair,
  // which the SLP vectoriser would pack into a 2-wide vector (and then the loop is not vectorised).
  const float smaller = with_sign_of(fmin(fabs(before), fmax(after, -after)), before);
  return before * after > 0.0f ? smaller : 0.0f;
}
typedef struct {
  float bed, depth;
} CellSlopes;
ALWAYS_INLINE CellSlopes bed_and_depth_slopes(const __global float* height_view, const __global float* depth,
                                              const __global float* rain_weight, float rain, int k, int stride,
                                              int n, int has_both) {
  const int a = max(k - stride, 0), b = min(k + stride, n - 1);
  const float ha = depth[a] + rain * RAIN_WEIGHT(rain_weight, a), hk = depth[k] + rain * RAIN_WEIGHT(rain_weight, k),
              hb = depth[b] + rain * RAIN_WEIGHT(rain_weight, b);
  const float za = height_view[a], zk = height_view[k], zb = height_view[b];
  // First order at the map's edges and wherever a neighbour is dry.
  const float full = has_both && fmin(ha, fmin(hk, hb)) > GODUNOV_DRY ? 1.0f : 0.0f;
  const float bed = full * minmod(zk - za, zb - zk), dh = minmod(hk - ha, hb - hk);
  CellSlopes s;
  s.bed = bed;
  s.depth = with_sign_of(fmin(fabs(dh), fabs(bed)), dh);
  return s;
}

// A face between cells a (left or upper) and b: the mass flux, the normal momentum flux as a and as
// b see it (Audusse's correction g/2 (h² − h*²) of each side's own depth at the face against the
// reconstructed one), the tangential momentum flux.
typedef struct {
  float mass, momentum_a, momentum_b, tangential;
} GodunovFace;

// The face from each side's bed and depth at the face, and its velocities (normal, tangential),
// on Audusse's reconstruction.
ALWAYS_INLINE GodunovFace reconstructed_face(float za, float ha, float una, float uta, float zb, float hb, float unb,
                                             float utb) {
  const float z = fmax(za, zb);
  const float ha_star = fmax(0.0f, ha + za - z), hb_star = fmax(0.0f, hb + zb - z);
  const HllFlux f = hll_flux(ha_star, una, uta, hb_star, unb, utb);
  const float half_g = 0.5f * PIPE_GRAVITY;
  GodunovFace face;
  face.mass = f.mass;
  face.momentum_a = f.momentum + half_g * (ha * ha - ha_star * ha_star);
  face.momentum_b = f.momentum + half_g * (hb * hb - hb_star * hb_star);
  face.tangential = f.tangential;
  return face;
}

// One of two faces, per member: the loop vectoriser's select.
ALWAYS_INLINE GodunovFace face_if(int condition, GodunovFace yes, GodunovFace no) {
  GodunovFace face;
  face.mass = condition ? yes.mass : no.mass;
  face.momentum_a = condition ? yes.momentum_a : no.momentum_a;
  face.momentum_b = condition ? yes.momentum_b : no.momentum_b;
  face.tangential = condition ? yes.tangential : no.tangential;
  return face;
}

// The flux through the map's edge after a cell (its right or lower face), for its depth and its
// normal and tangential velocities: against a mirror (closed) or a dry, lower ground (outflow).
ALWAYS_INLINE HllFlux edge_flux_after(float h, float un, float ut) {
#if PIPE_CLOSED
  return hll_flux(h, un, ut, h, -un, ut);
#else
  return hll_flux(h, un, ut, 0.0f, 0.0f, 0.0f);
#endif
}

// The same before a cell (its left or upper face), which no cell owns.
ALWAYS_INLINE HllFlux edge_flux_before(float h, float un, float ut) {
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
  const CellSlopes sx = bed_and_depth_slopes(height_view, depth, rain_weight, rain, k, 1, n, i > 0 && i < nx - 1);
  const CellSlopes sz = bed_and_depth_slopes(height_view, depth, rain_weight, rain, k, nx, n, j > 0 && j < ny - 1);
  slopes[0 * n + k] = sx.bed, slopes[1 * n + k] = sx.depth, slopes[2 * n + k] = sz.bed, slopes[3 * n + k] = sz.depth;
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
  const float sx_bed = slopes[0 * n + k], sx_depth = slopes[1 * n + k];
  const float sz_bed = slopes[2 * n + k], sz_depth = slopes[3 * n + k];
  // Right face (x) and lower face (z, normal velocity v, tangential u), between this cell and its
  // neighbour; a cell on the map's edge reads itself there, and pipe_godunov_edges then writes the
  // edge's own flux over that face.
  const int r = i < nx - 1 ? k + 1 : k, l = j < ny - 1 ? k + nx : k;
  const GodunovFace fx =
      reconstructed_face(z + 0.5f * sx_bed, h + 0.5f * sx_depth, u, v, height_view[r] - 0.5f * slopes[0 * n + r],
                         depth[r] + rain * RAIN_WEIGHT(rain_weight, r) - 0.5f * slopes[1 * n + r], velocity[r],
                         velocity[n + r]);
  const GodunovFace fz =
      reconstructed_face(z + 0.5f * sz_bed, h + 0.5f * sz_depth, v, u, height_view[l] - 0.5f * slopes[2 * n + l],
                         depth[l] + rain * RAIN_WEIGHT(rain_weight, l) - 0.5f * slopes[3 * n + l], velocity[n + l],
                         velocity[l]);
  face_flux[0 * n + k] = fx.mass, face_flux[1 * n + k] = fx.momentum_a, face_flux[2 * n + k] = fx.momentum_b;
  face_flux[3 * n + k] = fx.tangential;
  face_flux[4 * n + k] = fz.mass, face_flux[5 * n + k] = fz.momentum_a, face_flux[6 * n + k] = fz.momentum_b;
  face_flux[7 * n + k] = fz.tangential;
}

// The faces on the map's edges, one work-item a face: against a mirror (closed) or a dry, lower
// ground (outflow). The faces after a cell (the last column's right, the last row's lower) go into
// face_flux over what pipe_godunov_faces left there; the faces before one (the first column's left,
// the first row's upper), which no cell owns, into edge_before (mass, momentum, tangential; the
// rows' left faces first, then the columns' upper faces).
__kernel void pipe_godunov_edges(const __global float* depth, const __global float* velocity,
                                 __global float* face_flux, __global float* edge_before, const int nx,
                                 const int ny, const float dt, const __global float* rain_weight,
                                 const float rain_on) {
  const int e = get_global_id(0), n = nx * ny;
  if (e >= 2 * (nx + ny)) return;
  const int in_rows = e < 2 * ny, line = in_rows ? e >> 1 : (e - 2 * ny) >> 1, after = e & 1;
  const int k = in_rows ? line * nx + (after ? nx - 1 : 0) : (after ? (ny - 1) * nx : 0) + line;
  const float h = depth[k] + dt * PIPE_RAIN * rain_on * RAIN_WEIGHT(rain_weight, k);
  // Along a row the face's normal velocity is u, along a column v.
  const float un = in_rows ? velocity[k] : velocity[n + k], ut = in_rows ? velocity[n + k] : velocity[k];
  if (after) {
    const HllFlux f = edge_flux_after(h, un, ut);
    const int plane = in_rows ? 0 : 4;
    face_flux[(plane + 0) * n + k] = f.mass, face_flux[(plane + 1) * n + k] = f.momentum;
    face_flux[(plane + 2) * n + k] = f.momentum, face_flux[(plane + 3) * n + k] = f.tangential;
  } else {
    const HllFlux f = edge_flux_before(h, un, ut);
    const int at = 3 * (in_rows ? line : ny + line);
    edge_before[at] = f.mass, edge_before[at + 1] = f.momentum, edge_before[at + 2] = f.tangential;
  }
}

__kernel void pipe_godunov_update(__global float* depth, __global float* velocity, __global float* flux,
                                  const __global float* face_flux, const __global float* edge_before,
                                  const __global float* slopes,
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
  // The left and upper faces: the neighbour's, or on the map's edge pipe_godunov_edges' (both read,
  // one kept: a load under a branch stops the loop vectoriser).
  const int kl = i > 0 ? k - 1 : k, ku = j > 0 ? k - nx : k, el = 3 * j, eu = 3 * (ny + i);
  const GodunovFace left = face_if(
      i > 0, (GodunovFace){face_flux[0 * n + kl], 0.0f, face_flux[2 * n + kl], face_flux[3 * n + kl]},
      (GodunovFace){edge_before[el], 0.0f, edge_before[el + 1], edge_before[el + 2]});
  const GodunovFace upper = face_if(
      j > 0, (GodunovFace){face_flux[4 * n + ku], 0.0f, face_flux[6 * n + ku], face_flux[7 * n + ku]},
      (GodunovFace){edge_before[eu], 0.0f, edge_before[eu + 1], edge_before[eu + 2]});
  const float s = dt / cell;
  const float h_new = fmax(0.0f, h - s * (right.mass - left.mass + lower.mass - upper.mass));
  // The momentum: the faces' fluxes and the bed's centred source g h Δz over the cell.
  float qx = h * u - s * (right.momentum_a - left.momentum_b + lower.tangential - upper.tangential +
                          g * h * slopes[0 * n + k]);
  float qz = h * v - s * (lower.momentum_a - upper.momentum_b + right.tangential - left.tangential +
                          g * h * slopes[2 * n + k]);
  const int wet = h_new > GODUNOV_DRY;
  float un = qx / h_new, vn = qz / h_new;
#if PIPE_FRICTION_ON
  // Manning's friction, implicitly: u /= 1 + Δt g n² |u| / d^(4/3).
  const float third = pipe_inverse_cbrt(fmax(h_new, 1e-3f));
  const float speed = sqrt(un * un + vn * vn);
  const float damp = 1.0f + dt * PIPE_GRAVITY_N2 * speed * third * third * third * third;
  un /= damp, vn /= damp;
#endif
  un = wet ? un : 0.0f, vn = wet ? vn : 0.0f;  // dry water has no velocity (the division's NaN dropped)
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
