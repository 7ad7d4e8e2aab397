// SPDX-License-Identifier: MIT
// Thermal relaxation (talus; Musgrave 1989, Olsen 2004; physics.md §4 and models.md "thermal").
// Where a vertex stands more than T above a 4-neighbour (T = cell·tan(talus angle)), it sheds
//   c · (d_max − T)
// split among its lower neighbours in proportion to their excess (d_i − T). Two passes so the
// result does not depend on order: thermal_outflow computes every vertex's four outflows; then
// thermal_gather moves them (the vertex loses its outflows, gains its neighbours' inflows). All
// amounts are integer counts of the height quantum, so volume is conserved exactly. The outflows are
// stored one plane per direction (L R T B: outflow[d·n + k]), so that both passes read them contiguously.
// With a layer stack (GROUND = 1, docs/layers.md) the threshold is the exposed material's (talus_field,
// quanta), and the amount shed is the bed's detachment of c·(d_max − T): its loose sediment first, then
// its rock, each at its own erodibility (0 where frozen), never more than c = 1 would shed.
// Height-aware variant (HEIGHT_AWARE = 1): the threshold grows with height,
//   T(h) = T · (1 + hardness · (h − h_min)/(h_max − h_min)), which keeps peaks sharp.

__kernel void thermal_outflow(const __global long* height, __global long* outflow, const int nx, const int ny,
                              const long talus, const float rate, const int height_aware, const float hardness,
                              const long h_min, const long h_range, const __global float* rock_erodibility,
                              const __global float* sediment_erodibility, const __global long* ground_sediment,
                              const __global long* talus_field) {
  const int k = get_global_id(0), n = nx * ny;
  if (k >= n) return;
  const int j = grid_row(k, nx), i = k - j * nx;
  const long h = height[k];
  long threshold = GROUND ? talus_field[k] : talus;
  if (height_aware && h_range > 0) {
    threshold = (long)((float)threshold * (1.0f + hardness * (float)(h - h_min) / (float)h_range));
  }
  // A neighbour outside the map reads the vertex itself: a drop of 0, never above the threshold (≥ 0).
  // Scalars and selects rather than arrays and branches: the loop over vertices vectorises.
  const long drop_l = h - (i > 0 ? height[k - 1] : h), drop_r = h - (i < nx - 1 ? height[k + 1] : h);
  const long drop_t = h - (j > 0 ? height[k - nx] : h), drop_b = h - (j < ny - 1 ? height[k + nx] : h);
  const long excess_l = max(drop_l - threshold, 0L), excess_r = max(drop_r - threshold, 0L);
  const long excess_t = max(drop_t - threshold, 0L), excess_b = max(drop_b - threshold, 0L);
  const long excess_sum = excess_l + excess_r + excess_t + excess_b;
  const long d_max = max(max(drop_l, drop_r), max(drop_t, drop_b));
  // Both amounts are ≥ 0, so truncation is the floor (and, unlike floor(), vectorises).
  const float shed = fmin(BED_DETACHMENT(rate * (float)(d_max - threshold), k), (float)(d_max - threshold));
  const long total = excess_sum > 0 ? (long)shed : 0;
  const float sum = (float)max(excess_sum, 1L);
  outflow[0 * n + k] = (long)((float)total * ((float)excess_l / sum));
  outflow[1 * n + k] = (long)((float)total * ((float)excess_r / sum));
  outflow[2 * n + k] = (long)((float)total * ((float)excess_t / sum));
  outflow[3 * n + k] = (long)((float)total * ((float)excess_b / sum));
}

__kernel void thermal_gather(__global long* height, const __global long* outflow, const int nx, const int ny) {
  const int k = get_global_id(0), n = nx * ny;
  if (k >= n) return;
  const int j = grid_row(k, nx), i = k - j * nx;
  // The neighbour's outflow towards this vertex is in the opposite direction (d ^ 1); outside the map
  // there is no neighbour and nothing flows in.
  const long in = (i > 0 ? outflow[1 * n + k - 1] : 0) + (i < nx - 1 ? outflow[0 * n + k + 1] : 0) +
                  (j > 0 ? outflow[3 * n + k - nx] : 0) + (j < ny - 1 ? outflow[2 * n + k + nx] : 0);
  const long out = outflow[0 * n + k] + outflow[1 * n + k] + outflow[2 * n + k] + outflow[3 * n + k];
  height[k] += in - out;
}
