// SPDX-License-Identifier: MIT
// Cellular-automaton hydraulic erosion (Olsen 2004; models.md "olsen"), one iteration in four
// kernels so that cells exchanging material never race: terrain height (height_fixed) and suspended
// sediment (sediment) are integer counts of the height quantum, so h + s is conserved exactly;
// water (m) is a float. Edges are closed: nothing leaves the map.
//   1 olsen_dissolve:  w += K_r;  m = K_s·w;  h −= m, s += m
//   2 olsen_outflow:   water moves to lower 4-neighbours in proportion to the drops of a = h + w,
//                      at most min(w, a − ā) in all (ā the mean of the cell and its lower neighbours);
//                      sediment goes with it in proportion to the water
//   3 olsen_gather:    each cell loses its outflows and gains its neighbours' inflows
//   4 olsen_settle:    w *= 1 − K_e; the sediment above capacity K_c·w is deposited
// Compile-time constants (host -D): OLSEN_RAIN, OLSEN_SOLUBILITY, OLSEN_EVAPORATION, OLSEN_CAPACITY (m
// or fractions, per iteration).

__constant int2 kOlsenNeighbour[4] = {(int2)(-1, 0), (int2)(1, 0), (int2)(0, -1), (int2)(0, 1)};

__kernel void olsen_dissolve(__global long* height, __global float* water, __global long* sediment, const int n,
                             const float quantum) {
  const int k = get_global_id(0);
  if (k >= n) return;
  const float w = water[k] + OLSEN_RAIN;
  water[k] = w;
  const long m = (long)floor(OLSEN_SOLUBILITY * w / quantum);
  height[k] -= m;
  sediment[k] += m;
}

__kernel void olsen_outflow(const __global long* height, const __global float* water, const __global long* sediment,
                            __global float* out_water, __global long* out_sediment, const int nx, const int ny,
                            const float quantum) {
  const int k = get_global_id(0);
  if (k >= nx * ny) return;
  const int i = k % nx, j = k / nx;
  const float w = water[k];
  const float a = (float)height[k] * quantum + w;
  float drop[4];
  float total = 0.0f, sum_lower = a;
  int lower = 1;
  for (int d = 0; d < 4; ++d) {
    drop[d] = 0.0f;
    const int x = i + kOlsenNeighbour[d].x, z = j + kOlsenNeighbour[d].y;
    if (x < 0 || z < 0 || x >= nx || z >= ny) continue;
    const int m = z * nx + x;
    const float an = (float)height[m] * quantum + water[m];
    if (an < a) {
      drop[d] = a - an;
      total += drop[d];
      sum_lower += an;
      ++lower;
    }
  }
  const float moved = total > 0.0f ? fmin(w, a - sum_lower / (float)lower) : 0.0f;
  long sediment_given = 0;
  for (int d = 0; d < 4; ++d) {
    const float share = total > 0.0f ? moved * drop[d] / total : 0.0f;
    out_water[4 * k + d] = share;
    const long s = (w > 0.0f && share > 0.0f) ? min((long)floor((float)sediment[k] * (share / w)), sediment[k] - sediment_given) : 0;
    out_sediment[4 * k + d] = s;
    sediment_given += s;
  }
}

__kernel void olsen_gather(__global float* water, __global long* sediment, const __global float* out_water,
                           const __global long* out_sediment, const int nx, const int ny) {
  const int k = get_global_id(0);
  if (k >= nx * ny) return;
  const int i = k % nx, j = k / nx;
  float w = water[k];
  long s = sediment[k];
  for (int d = 0; d < 4; ++d) {
    w -= out_water[4 * k + d];
    s -= out_sediment[4 * k + d];
    const int x = i + kOlsenNeighbour[d].x, z = j + kOlsenNeighbour[d].y;
    if (x < 0 || z < 0 || x >= nx || z >= ny) continue;
    const int m = z * nx + x;
    w += out_water[4 * m + (d ^ 1)];  // the neighbour's flow towards this cell
    s += out_sediment[4 * m + (d ^ 1)];
  }
  water[k] = fmax(w, 0.0f);
  sediment[k] = s;
}

__kernel void olsen_settle(__global long* height, __global float* water, __global long* sediment, const int n,
                           const float quantum) {
  const int k = get_global_id(0);
  if (k >= n) return;
  const float w = water[k] * (1.0f - OLSEN_EVAPORATION);
  water[k] = w;
  const long capacity = (long)floor(OLSEN_CAPACITY * w / quantum);
  const long excess = sediment[k] - capacity;
  if (excess > 0) {
    height[k] += excess;
    sediment[k] -= excess;
  }
}
