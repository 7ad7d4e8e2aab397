// SPDX-License-Identifier: MIT
// Thermal relaxation (talus; Musgrave 1989, Olsen 2004; physics.md §4 and models.md "thermal").
// Where a vertex stands more than T above a 4-neighbour (T = cell·tan(talus angle)), it sheds
//   c · (d_max − T)
// split among its lower neighbours in proportion to their excess (d_i − T). Two passes so the
// result does not depend on order: thermal_outflow computes every vertex's four outflows; then
// thermal_gather moves them (the vertex loses its outflows, gains its neighbours' inflows). All
// amounts are integer counts of the height quantum, so volume is conserved exactly.
// Height-aware variant (HEIGHT_AWARE = 1): the threshold grows with height,
//   T(h) = T · (1 + hardness · (h − h_min)/(h_max − h_min)), which keeps peaks sharp.

__constant int2 kNeighbour[4] = {(int2)(-1, 0), (int2)(1, 0), (int2)(0, -1), (int2)(0, 1)};

__kernel void thermal_outflow(const __global long* height, __global long* outflow, const int nx, const int ny,
                              const long talus, const float rate, const int height_aware, const float hardness,
                              const long h_min, const long h_range) {
  const int k = get_global_id(0);
  if (k >= nx * ny) return;
  const int i = k % nx, j = k / nx;
  const long h = height[k];
  long threshold = talus;
  if (height_aware && h_range > 0) {
    threshold = (long)((float)talus * (1.0f + hardness * (float)(h - h_min) / (float)h_range));
  }
  long excess[4];
  long d_max = 0, excess_sum = 0;
  for (int d = 0; d < 4; ++d) {
    const int a = i + kNeighbour[d].x, b = j + kNeighbour[d].y;
    excess[d] = 0;
    if (a < 0 || b < 0 || a >= nx || b >= ny) continue;
    const long diff = h - height[b * nx + a];
    if (diff > threshold) {
      excess[d] = diff - threshold;
      excess_sum += excess[d];
      d_max = max(d_max, diff);
    }
  }
  const long total = excess_sum > 0 ? (long)floor(rate * (float)(d_max - threshold)) : 0;
  for (int d = 0; d < 4; ++d) {
    outflow[4 * k + d] = excess_sum > 0 ? (long)floor((float)total * ((float)excess[d] / (float)excess_sum)) : 0;
  }
}

__kernel void thermal_gather(__global long* height, const __global long* outflow, const int nx, const int ny) {
  const int k = get_global_id(0);
  if (k >= nx * ny) return;
  const int i = k % nx, j = k / nx;
  long change = 0;
  for (int d = 0; d < 4; ++d) {
    change -= outflow[4 * k + d];
    const int a = i + kNeighbour[d].x, b = j + kNeighbour[d].y;
    if (a < 0 || b < 0 || a >= nx || b >= ny) continue;
    // The neighbour's outflow towards this vertex is in the opposite direction: d ^ 1.
    change += outflow[4 * (b * nx + a) + (d ^ 1)];
  }
  height[k] += change;
}
