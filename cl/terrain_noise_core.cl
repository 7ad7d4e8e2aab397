// SPDX-License-Identifier: MIT
// The noise families of the terrain generators (docs/generators.md), in float arithmetic that gives
// the same bits on every device: integer hashing, + − × and floor only (no library transcendental,
// whose last bits differ between devices; fused multiply-adds switched off). This file is OpenCL C
// and C++ at once: cl/terrain_noise.cl evaluates it on the device, src/runnel/terrain/noise_family.cpp
// on the host as the oracle the tests compare the device with, bit for bit.
//   value noise (Münch 2011's "Perlin noise"): random values at lattice points, interpolated
//     linearly or with the cosine curve (1 − cos πt)/2 (a degree-9 polynomial, error < 4e-6)
//   gradient noise (Perlin 1985, with Perlin 2002's quintic fade): 8 hashed unit gradients
//   family 0 value-noise fBm, 1 turbulence (Σ|noise|), 2 multifractal (Musgrave's multiplicative),
//   3 hybrid multifractal, 4 heterogeneous terrain (Musgrave 1994), 5 fBm with a Hurst exponent that
//   varies with position or with the height of the first octaves (Jourdan 2008)

#ifndef RUNNEL_NOISE_HOST
#pragma OPENCL FP_CONTRACT OFF
#define NOISE_FLOOR floor
#define NOISE_FABS fabs
#define NOISE_GLOBAL __global
#endif

// The octave amplitude table of family 5: amplitudes of octave o at 17 Hurst exponents from H1 to H2.
#define NOISE_MAX_OCTAVES 24
#define NOISE_H_STEPS 17

typedef struct {
  int family;        // 0..5, as above
  int octaves;       // ≤ NOISE_MAX_OCTAVES
  int cosine;        // value noise: cosine (1) or linear (0) interpolation
  int by_height;     // family 5: H from the first octaves' height (1) or from x (0)
  float frequency;   // cycles per metre of the first octave
  float lacunarity;  // frequency ratio between octaves
  float gain;        // amplitude ratio between octaves, lacunarity^−H
  float offset;      // multifractal offset
  float extent_x;    // m: family 5 by position, H1 at x = 0 and H2 at x = extent_x
  uint seed_lo, seed_hi;
} NoiseParams;

// A 32-bit mix (Wang/Jenkins style, full avalanche) of the lattice point, the octave and the seed.
inline uint noise_hash(int ix, int iy, uint octave, uint seed_lo, uint seed_hi) {
  uint h = (uint)ix * 0x8da6b343u ^ (uint)iy * 0xd8163841u ^ octave * 0xcb1ab31fu ^ seed_lo;
  h ^= seed_hi * 0x9e3779b9u;
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return h;
}

// Uniform in [−1, 1) with 24 bits.
inline float noise_unit(uint h) {
  return (float)(h >> 8) * (2.0f / 16777216.0f) - 1.0f;
}

// (1 − cos πt)/2 through sin: 0.5 + 0.5·sin(π(t − ½)), sin by its Taylor series to x⁹.
inline float noise_cosine_curve(float t) {
  const float x = 3.14159265f * (t - 0.5f), x2 = x * x;
  const float s = x * (1.0f + x2 * (-1.0f / 6.0f + x2 * (1.0f / 120.0f + x2 * (-1.0f / 5040.0f + x2 * (1.0f / 362880.0f)))));
  return 0.5f + 0.5f * s;
}

inline float noise_fade(float t) {  // 6t⁵ − 15t⁴ + 10t³: C2 at the lattice
  return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}

inline float value_noise(float x, float y, uint octave, int cosine, uint seed_lo, uint seed_hi) {
  const float fx = NOISE_FLOOR(x), fy = NOISE_FLOOR(y);
  const int ix = (int)fx, iy = (int)fy;
  float u = x - fx, v = y - fy;
  if (cosine) {
    u = noise_cosine_curve(u);
    v = noise_cosine_curve(v);
  }
  const float a = noise_unit(noise_hash(ix, iy, octave, seed_lo, seed_hi));
  const float b = noise_unit(noise_hash(ix + 1, iy, octave, seed_lo, seed_hi));
  const float c = noise_unit(noise_hash(ix, iy + 1, octave, seed_lo, seed_hi));
  const float d = noise_unit(noise_hash(ix + 1, iy + 1, octave, seed_lo, seed_hi));
  const float top = a + (b - a) * u, bottom = c + (d - c) * u;
  return top + (bottom - top) * v;
}

// The dot product of a hashed unit gradient (one of 8) with (dx, dy).
inline float noise_gradient_dot(uint h, float dx, float dy) {
  const float r = 0.70710678f;
  switch (h >> 29) {
    case 0: return dx;
    case 1: return -dx;
    case 2: return dy;
    case 3: return -dy;
    case 4: return r * dx + r * dy;
    case 5: return r * dx - r * dy;
    case 6: return -r * dx + r * dy;
    default: return -r * dx - r * dy;
  }
}

// In about [−0.7, 0.7], zero at the lattice points.
inline float gradient_noise_f(float x, float y, uint octave, uint seed_lo, uint seed_hi) {
  const float fx = NOISE_FLOOR(x), fy = NOISE_FLOOR(y);
  const int ix = (int)fx, iy = (int)fy;
  const float dx = x - fx, dy = y - fy;
  const float n00 = noise_gradient_dot(noise_hash(ix, iy, octave, seed_lo, seed_hi), dx, dy);
  const float n10 = noise_gradient_dot(noise_hash(ix + 1, iy, octave, seed_lo, seed_hi), dx - 1.0f, dy);
  const float n01 = noise_gradient_dot(noise_hash(ix, iy + 1, octave, seed_lo, seed_hi), dx, dy - 1.0f);
  const float n11 = noise_gradient_dot(noise_hash(ix + 1, iy + 1, octave, seed_lo, seed_hi), dx - 1.0f, dy - 1.0f);
  const float u = noise_fade(dx), v = noise_fade(dy);
  const float top = n00 + (n10 - n00) * u, bottom = n01 + (n11 - n01) * u;
  return top + (bottom - top) * v;
}

// The unnormalised height of a noise family at (x, y) metres. `amplitudes` is family 5's table
// (NOISE_H_STEPS rows of `octaves` amplitudes, H from H1 to H2).
inline float noise_family_height(const NoiseParams* p, float x, float y, const NOISE_GLOBAL float* amplitudes) {
  float freq = p->frequency, amp = 1.0f, sum = 0.0f;
  if (p->family == 0) {
    for (int o = 0; o < p->octaves; ++o) {
      sum += amp * value_noise(x * freq, y * freq, (uint)o, p->cosine, p->seed_lo, p->seed_hi);
      freq *= p->lacunarity;
      amp *= p->gain;
    }
    return sum;
  }
  if (p->family == 1) {
    for (int o = 0; o < p->octaves; ++o) {
      sum += amp * NOISE_FABS(gradient_noise_f(x * freq, y * freq, (uint)o, p->seed_lo, p->seed_hi));
      freq *= p->lacunarity;
      amp *= p->gain;
    }
    return sum;
  }
  if (p->family == 2) {  // value = Π (offset + noise·amplitude): each octave modulates the ones before
    float value = 1.0f;
    for (int o = 0; o < p->octaves; ++o) {
      value *= p->offset + gradient_noise_f(x * freq, y * freq, (uint)o, p->seed_lo, p->seed_hi) * amp;
      freq *= p->lacunarity;
      amp *= p->gain;
    }
    return value;
  }
  if (p->family == 3) {  // hybrid: each octave weighted by what the ones before built up
    float result = gradient_noise_f(x * freq, y * freq, 0u, p->seed_lo, p->seed_hi) + p->offset;
    float weight = result;
    for (int o = 1; o < p->octaves; ++o) {
      freq *= p->lacunarity;
      amp *= p->gain;
      weight = weight > 1.0f ? 1.0f : weight;
      const float signal = (gradient_noise_f(x * freq, y * freq, (uint)o, p->seed_lo, p->seed_hi) + p->offset) * amp;
      result += weight * signal;
      weight *= signal;
    }
    return result;
  }
  if (p->family == 4) {  // heterogeneous: each octave scaled by the height so far
    float value = p->offset + gradient_noise_f(x * freq, y * freq, 0u, p->seed_lo, p->seed_hi);
    for (int o = 1; o < p->octaves; ++o) {
      freq *= p->lacunarity;
      amp *= p->gain;
      value += (gradient_noise_f(x * freq, y * freq, (uint)o, p->seed_lo, p->seed_hi) + p->offset) * amp * value;
    }
    return value;
  }
  // Family 5: fBm whose Hurst exponent moves from H1 to H2 with x, or with the height of the first
  // two octaves (their sum mapped from [−1, 1] to [0, 1]).
  float t;
  if (p->by_height) {
    const float first = gradient_noise_f(x * freq, y * freq, 0u, p->seed_lo, p->seed_hi) +
                        0.5f * gradient_noise_f(x * freq * p->lacunarity, y * freq * p->lacunarity, 1u,
                                                p->seed_lo, p->seed_hi);
    t = 0.5f + first * (0.5f / 1.05f);
  } else {
    t = x / p->extent_x;
  }
  t = t < 0.0f ? 0.0f : (t > 1.0f ? 1.0f : t);
  const float row = t * (float)(NOISE_H_STEPS - 1);
  int r0 = (int)row;
  r0 = r0 > NOISE_H_STEPS - 2 ? NOISE_H_STEPS - 2 : r0;
  const float w = row - (float)r0;
  for (int o = 0; o < p->octaves; ++o) {
    const float a0 = amplitudes[r0 * p->octaves + o], a1 = amplitudes[(r0 + 1) * p->octaves + o];
    sum += (a0 + (a1 - a0) * w) * gradient_noise_f(x * freq, y * freq, (uint)o, p->seed_lo, p->seed_hi);
    freq *= p->lacunarity;
  }
  return sum;
}
