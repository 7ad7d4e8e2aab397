// SPDX-License-Identifier: MIT
// The footprint of a particle on the terrain's vertices: where its erosion and deposition land
// (erode.cl) and where its water is counted (water_depth.cl). The vertices within FOOTPRINT_RADIUS
// of the particle (at least the smoothing length's support, and 2 cells, so every particle reaches
// several vertices whatever its size), weighted by a smooth, separable function of the distances.
// Compile-time constants (host -D): FOOTPRINT_RADIUS (m), FOOTPRINT_SIDE (vertices).

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

// The shares of `quanta` that the footprint f of (x, z) gives its vertices: ADD(i, j, share) for
// each vertex (i, j) that receives some. Each vertex k receives quanta·w_k/Σw in expectation, and
// all of them exactly `quanta` together: systematic sampling, vertex k gets
// floor(quanta·C_k + u) − floor(quanta·C_(k−1) + u) with C the cumulative normalised weight and u in
// [0, 1). Small amounts land on the vertices in proportion to their weights, not all on the nearest.
// With a `factor` field (not null), vertex k's weight is w_k·factor[k] and factor_mean is
// Σ w_k·factor[k] / Σ w_k (footprint_mean_float): erosion taken from a layered bed comes from its
// vertices in proportion to their erodibility, and none from a frozen one. f must reach a vertex.
// A macro, so that the shares go wherever the caller adds them (global atomics, a private box)
// through the same float arithmetic (a private array of shares in between made the water pass 40 %
// slower).
#define FOR_EACH_FOOTPRINT_SHARE(f, nx, cell, x, z, quanta, u, factor, factor_mean, ADD)                          \
  do {                                                                                                       \
    const float scale_ = (float)(quanta) / ((f).sum_x * (f).sum_z * ((factor) ? (factor_mean) : 1.0f));      \
    float cumulative_ = 0.0f, best_weight_ = 0.0f;                                                           \
    long given_ = 0;                                                                                         \
    int best_i_ = -1, best_j_ = -1;                                                                          \
    for (int j_ = (f).j0; j_ <= (f).j1; ++j_) {                                                              \
      const float wz_ = footprint_weight((float)j_ * (cell) - (z));                                          \
      for (int i_ = (f).i0; i_ <= (f).i1; ++i_) {                                                            \
        /* Without a factor, the sum exactly as it always was: one statement, which the compiler may     */ \
        /* contract into a fused multiply-add (splitting it changed every SPH run in the last bits).     */ \
        float w_ = 1.0f;                                                                                     \
        if (factor) {                                                                                        \
          w_ = wz_ * footprint_weight((float)i_ * (cell) - (x)) * (factor)[j_ * (nx) + i_];                  \
          cumulative_ += w_;                                                                                 \
          if (w_ > best_weight_) {                                                                           \
            best_weight_ = w_;                                                                               \
            best_i_ = i_;                                                                                    \
            best_j_ = j_;                                                                                    \
          }                                                                                                  \
        } else {                                                                                             \
          cumulative_ += wz_ * footprint_weight((float)i_ * (cell) - (x));                                   \
        }                                                                                                    \
        /* Round-off's remainder: the last vertex takes it, or, where a factor gives that one no weight, */ \
        /* the heaviest (a factor of 1 everywhere changes nothing, bit for bit).                         */ \
        const long upto_ = (i_ == (f).i1 && j_ == (f).j1 && (!(factor) || w_ > 0.0f))                       \
                               ? (quanta)                                                                    \
                               : min((long)(quanta), (long)floor(cumulative_ * scale_ + (u)));               \
        if (upto_ > given_) {                                                                                \
          ADD(i_, j_, upto_ - given_);                                                                       \
          given_ = upto_;                                                                                    \
        }                                                                                                    \
      }                                                                                                      \
    }                                                                                                        \
    if ((factor) && given_ < (quanta) && best_i_ >= 0) ADD(best_i_, best_j_, (quanta) - given_);             \
  } while (0)

// The vertex of last resort for a point whose footprint reaches no vertex (off the grid's edge).
inline int footprint_fallback_vertex(int nx, int ny, float cell, float x, float z) {
  return clamp((int)round(z / cell), 0, ny - 1) * nx + clamp((int)round(x / cell), 0, nx - 1);
}

// Adds sign·quanta to the vertices of the footprint of (x, z), shared out as FOR_EACH_FOOTPRINT_SHARE
// says, with one atomic add a vertex.
inline void spread_quanta(volatile __global long* target, int nx, int ny, float cell, float x, float z, long quanta,
                          long sign, float u, const __global float* factor, float factor_mean) {
  if (quanta == 0) return;
  const Footprint f = footprint_of(x, z, nx, ny, cell);
  if (!(f.sum_x > 0.0f && f.sum_z > 0.0f)) {
    atom_add(&target[footprint_fallback_vertex(nx, ny, cell, x, z)], sign * quanta);
    return;
  }
#define SPREAD_QUANTA_ADD(i, j, share) atom_add(&target[(j) * nx + (i)], sign * (share))
  FOR_EACH_FOOTPRINT_SHARE(f, nx, cell, x, z, quanta, u, factor, factor_mean, SPREAD_QUANTA_ADD);
#undef SPREAD_QUANTA_ADD
}

// The footprint-weighted mean of a float vertex field at (x, z); the nearest vertex's value off the
// grid's edge. Both sums run in the same order, so a field of 1 everywhere has a mean of exactly 1.
inline float footprint_mean_float(const __global float* field, int nx, int ny, float cell, float x, float z) {
  const Footprint f = footprint_of(x, z, nx, ny, cell);
  if (!(f.sum_x > 0.0f && f.sum_z > 0.0f))
    return field[footprint_fallback_vertex(nx, ny, cell, x, z)];
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
