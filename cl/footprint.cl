// SPDX-License-Identifier: MIT
// The footprint of a particle on the terrain's vertices: where its erosion and deposition land
// (erode.cl) and where its water is counted (water_depth.cl). The vertices within FOOTPRINT_RADIUS
// of the particle (at least the smoothing length's support, and 2 cells, so every particle reaches
// several vertices whatever its size), weighted by a smooth, separable function of the distances.
// Compile-time constants (host -D): FOOTPRINT_RADIUS (m).

// The weight along one axis of a vertex at distance d: (1 − (d/R)²)² within R. A vertex's weight
// is the product over x and z: smooth, separable (its sum is the product of two short sums), cheap.
inline float footprint_weight(float d) {
  const float t = fmax(0.0f, 1.0f - d * d * (1.0f / (FOOTPRINT_RADIUS * FOOTPRINT_RADIUS)));
  return t * t;
}

// The vertices in reach of (x, z): [i0, i1] × [j0, j1], clamped to the grid, and the sums of the
// weights along each axis (a vertex's normalised weight is w_x·w_z / (sum_x·sum_z)). Empty when the
// point is off the grid by more than R (then sum_x or sum_z is 0).
typedef struct {
  int i0, i1, j0, j1;
  float sum_x, sum_z;
} Footprint;

inline Footprint footprint_of(float x, float z, int nx, int ny, float cell) {
  Footprint f;
  f.i0 = max(0, (int)ceil((x - FOOTPRINT_RADIUS) / cell));
  f.i1 = min(nx - 1, (int)floor((x + FOOTPRINT_RADIUS) / cell));
  f.j0 = max(0, (int)ceil((z - FOOTPRINT_RADIUS) / cell));
  f.j1 = min(ny - 1, (int)floor((z + FOOTPRINT_RADIUS) / cell));
  f.sum_x = 0.0f;
  f.sum_z = 0.0f;
  for (int i = f.i0; i <= f.i1; ++i) f.sum_x += footprint_weight((float)i * cell - x);
  for (int j = f.j0; j <= f.j1; ++j) f.sum_z += footprint_weight((float)j * cell - z);
  return f;
}

// Adds sign·quanta to the vertices of the footprint of (x, z), each vertex k receiving
// quanta·w_k/Σw in expectation, and exactly `quanta` together: systematic sampling, vertex k gets
// floor(quanta·C_k + u) − floor(quanta·C_(k−1) + u) with C the cumulative normalised weight and u in
// [0, 1). Small amounts land on the vertices in proportion to their weights, not all on the nearest.
// With a `factor` field (not null), vertex k's weight is w_k·factor[k] and factor_mean is
// Σ w_k·factor[k] / Σ w_k (footprint_mean_float): erosion taken from a layered bed comes from its
// vertices in proportion to their erodibility, and none from a frozen one.
inline void spread_quanta(volatile __global long* target, int nx, int ny, float cell, float x, float z, long quanta,
                          long sign, float u, const __global float* factor, float factor_mean) {
  if (quanta == 0) return;
  const Footprint f = footprint_of(x, z, nx, ny, cell);
  if (!(f.sum_x > 0.0f && f.sum_z > 0.0f)) {  // no vertex in reach (a particle off the grid's edge)
    const int k = clamp((int)round(z / cell), 0, ny - 1) * nx + clamp((int)round(x / cell), 0, nx - 1);
    atom_add(&target[k], sign * quanta);
    return;
  }
  const float scale = (float)quanta / (f.sum_x * f.sum_z * (factor ? factor_mean : 1.0f));
  float cumulative = 0.0f, best_weight = 0.0f;
  long given = 0;
  int best = -1;
  for (int j = f.j0; j <= f.j1; ++j) {
    const float wz = footprint_weight((float)j * cell - z);
    for (int i = f.i0; i <= f.i1; ++i) {
      // Without a factor, the sum exactly as it always was: one statement, which the compiler may
      // contract into a fused multiply-add (splitting it changed every SPH run in the last bits).
      float w = 1.0f;
      if (factor) {
        w = wz * footprint_weight((float)i * cell - x) * factor[j * nx + i];
        cumulative += w;
        if (w > best_weight) {
          best_weight = w;
          best = j * nx + i;
        }
      } else {
        cumulative += wz * footprint_weight((float)i * cell - x);
      }
      // Round-off's remainder: the last vertex takes it, or, where a factor gives that one no
      // weight, the heaviest (a factor of 1 everywhere changes nothing, bit for bit).
      const long upto = (i == f.i1 && j == f.j1 && (!factor || w > 0.0f))
                            ? quanta
                            : min(quanta, (long)floor(cumulative * scale + u));
      if (upto > given) {
        atom_add(&target[j * nx + i], sign * (upto - given));
        given = upto;
      }
    }
  }
  if (factor && given < quanta && best >= 0) atom_add(&target[best], sign * (quanta - given));
}

// The footprint-weighted mean of a float vertex field at (x, z); the nearest vertex's value off the
// grid's edge. Both sums run in the same order, so a field of 1 everywhere has a mean of exactly 1.
inline float footprint_mean_float(const __global float* field, int nx, int ny, float cell, float x, float z) {
  const Footprint f = footprint_of(x, z, nx, ny, cell);
  if (!(f.sum_x > 0.0f && f.sum_z > 0.0f))
    return field[clamp((int)round(z / cell), 0, ny - 1) * nx + clamp((int)round(x / cell), 0, nx - 1)];
  float sum = 0.0f, weights = 0.0f;
  for (int j = f.j0; j <= f.j1; ++j) {
    const float wz = footprint_weight((float)j * cell - z);
    for (int i = f.i0; i <= f.i1; ++i) {
      const float w = wz * footprint_weight((float)i * cell - x);
      sum += w * field[j * nx + i];
      weights += w;
    }
  }
  return sum / weights;
}

// The footprint-weighted mean of a vertex field (integer counts × unit) at (x, z).
inline float footprint_mean(const __global long* field, float unit, int nx, int ny, float cell, float x, float z) {
  const Footprint f = footprint_of(x, z, nx, ny, cell);
  if (!(f.sum_x > 0.0f && f.sum_z > 0.0f)) return 0.0f;
  float sum = 0.0f;
  for (int j = f.j0; j <= f.j1; ++j) {
    const float wz = footprint_weight((float)j * cell - z);
    for (int i = f.i0; i <= f.i1; ++i) sum += wz * footprint_weight((float)i * cell - x) * (float)field[j * nx + i];
  }
  return sum * unit / (f.sum_x * f.sum_z);
}
