// SPDX-License-Identifier: MIT
// Cellular-automaton hydraulic erosion (Olsen 2004; models.md "olsen"), one iteration in three
// kernels so that cells exchanging material never race: terrain height (height_fixed) and suspended
// sediment (sediment) are integer counts of the height quantum, so h + s is conserved exactly;
// water (m) is a float. Edges are closed: nothing leaves the map.
//   1 olsen_dissolve:  w += K_r;  m = K_s·w;  h −= m, s += m
//   2 olsen_outflow:   water moves to lower 4-neighbours in proportion to the drops of a = h + w,
//                      at most min(w, a − ā) in all (ā the mean of the cell and its lower neighbours);
//                      sediment goes with it in proportion to the water
//   3 olsen_gather_settle: each cell loses its outflows and gains its neighbours' inflows; then
//                      w *= 1 − K_e and the sediment above capacity K_c·w is deposited
// The outflows are stored one plane per direction (L R T B), read contiguously. Each plane has a row
// of zeros before and after the map (olsen_plane), so the gather reads its neighbours' outflows
// without a condition: beyond the top or bottom edge it reads the zero rows, beyond the left or right
// edge the last or first cell of the next row, whose outflow across the map's edge is always 0.
// olsen_outflow reads and writes 32-bit values only, so that PoCL runs it 8 or 16 cells at a time (a
// 64-bit load or store anywhere in a loop makes it 4 wide): olsen_dissolve leaves it each cell's level
// a as a float (the same expression it would evaluate) and the cell's sediment as at most
// OLSEN_SENDABLE quanta (host -D, 2^30: kOlsenSendable), and the sediment outflows are 32-bit. A
// cell holding more than that (over a kilometre of suspended sediment at the default quantum) sends
// shares of OLSEN_SENDABLE and keeps the rest; nothing is lost either way.
// Compile-time constants (host -D): OLSEN_RAIN, OLSEN_SOLUBILITY, OLSEN_EVAPORATION, OLSEN_CAPACITY (m
// or fractions, per iteration).

// Cell k's place in the outflow planes of direction d (the host allocates 4 (n + 2 nx) and zeroes them).
inline int olsen_plane(int d, int k, int nx, int n) { return d * (n + 2 * nx) + nx + k; }

// With a layer stack the dissolved amount is the bed's detachment (its loose sediment first, then its
// rock, each at its own erodibility), and with a rain mask the rain is scaled by the vertex's weight
// (docs/layers.md).
__kernel void olsen_dissolve(__global long* height, __global float* water, __global long* sediment, const int n,
                             const float quantum, const __global float* rock_erodibility,
                             const __global float* sediment_erodibility, const __global long* ground_sediment,
                             const __global float* rain_weight, const float rain_on, __global float* level,
                             __global int* sendable) {
  const int k = get_global_id(0);
  if (k >= n) return;
  const float w = water[k] + OLSEN_RAIN * rain_on * RAIN_WEIGHT(rain_weight, k);
  water[k] = w;
  const long m = (long)floor(BED_DETACHMENT(OLSEN_SOLUBILITY * w / quantum, k));
  const long h = height[k] - m, s = sediment[k] + m;
  height[k] = h;
  sediment[k] = s;
  level[k] = (float)h * quantum + w;
  sendable[k] = (int)min(s, OLSEN_SENDABLE);
}

// The water and sediment a cell sends to one lower neighbour (drop > 0); *given counts the sediment
// already sent, so that the four shares never add up to more than the cell has.
inline void olsen_send(float drop, float total, float moved, float w, int sediment, int* given,
                        __global float* out_water, __global int* out_sediment) {
  const float share = total > 0.0f ? moved * drop / total : 0.0f;
  // ≥ 0, so truncation is the floor (and, unlike floor(), vectorises); at most sediment·(1 + 2^-23),
  // within int range for sediment ≤ OLSEN_SENDABLE.
  const int s = (w > 0.0f && share > 0.0f) ? min((int)((float)sediment * (share / w)), sediment - *given) : 0;
  *out_water = share;
  *out_sediment = s;
  *given += s;
}

// Scalars and selects rather than arrays and branches, here and in olsen_gather_settle: the loop over
// cells vectorises. A neighbour outside the map reads the cell's own level, so it is never lower;
// adding the 0.0f of a neighbour that is not lower leaves every sum bit for bit as it was.
__kernel void olsen_outflow(const __global float* level, const __global float* water, const __global int* sendable,
                            __global float* out_water, __global int* out_sediment, const int nx, const int ny) {
  const int k = get_global_id(0), n = nx * ny;
  if (k >= n) return;
  const int j = grid_row(k, nx), i = k - j * nx;
  const float w = water[k];
  const float a = level[k];
  const float a_l = i > 0 ? level[k - 1] : a;
  const float a_r = i < nx - 1 ? level[k + 1] : a;
  const float a_t = j > 0 ? level[k - nx] : a;
  const float a_b = j < ny - 1 ? level[k + nx] : a;
  const float drop_l = a_l < a ? a - a_l : 0.0f, drop_r = a_r < a ? a - a_r : 0.0f;
  const float drop_t = a_t < a ? a - a_t : 0.0f, drop_b = a_b < a ? a - a_b : 0.0f;
  const float total = drop_l + drop_r + drop_t + drop_b;
  const float sum_lower =
      a + (a_l < a ? a_l : 0.0f) + (a_r < a ? a_r : 0.0f) + (a_t < a ? a_t : 0.0f) + (a_b < a ? a_b : 0.0f);
  const int lower = 1 + (a_l < a) + (a_r < a) + (a_t < a) + (a_b < a);
  const float moved = total > 0.0f ? fmin(w, a - sum_lower / (float)lower) : 0.0f;
  const int s = sendable[k];
  const int l = olsen_plane(0, k, nx, n), r = olsen_plane(1, k, nx, n);
  const int t = olsen_plane(2, k, nx, n), b = olsen_plane(3, k, nx, n);
  int given = 0;
  olsen_send(drop_l, total, moved, w, s, &given, out_water + l, out_sediment + l);
  olsen_send(drop_r, total, moved, w, s, &given, out_water + r, out_sediment + r);
  olsen_send(drop_t, total, moved, w, s, &given, out_water + t, out_sediment + t);
  olsen_send(drop_b, total, moved, w, s, &given, out_water + b, out_sediment + b);
}

__kernel void olsen_gather_settle(__global long* height, __global float* water, __global long* sediment,
                                  const __global float* out_water, const __global int* out_sediment, const int nx,
                                  const int ny, const float quantum) {
  const int k = get_global_id(0), n = nx * ny;
  if (k >= n) return;
  // Each cell loses its outflows and gains its neighbours' flows towards it (direction d ^ 1), in the
  // order L R T B.
  const int l = olsen_plane(0, k, nx, n), r = olsen_plane(1, k, nx, n);
  const int t = olsen_plane(2, k, nx, n), b = olsen_plane(3, k, nx, n);
  float w = water[k];
  w = w - out_water[l] + out_water[r - 1];
  w = w - out_water[r] + out_water[l + 1];
  w = w - out_water[t] + out_water[b - nx];
  w = w - out_water[b] + out_water[t + nx];
  // 32-bit outflows, summed in 64 bits.
  const long in = (long)out_sediment[r - 1] + (long)out_sediment[l + 1] + (long)out_sediment[b - nx] +
                  (long)out_sediment[t + nx];
  const long out = (long)out_sediment[l] + (long)out_sediment[r] + (long)out_sediment[t] + (long)out_sediment[b];
  // Settle: evaporation, then the sediment above the capacity of what is left is deposited.
  const float settled = fmax(w, 0.0f) * (1.0f - OLSEN_EVAPORATION);
  const long carried = sediment[k] + in - out;
  const long excess = max(carried - (long)floor(OLSEN_CAPACITY * settled / quantum), 0L);
  water[k] = settled;
  sediment[k] = carried - excess;
  height[k] += excess;
}
