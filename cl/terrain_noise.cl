// SPDX-License-Identifier: MIT
// The noise families of the terrain generators on the device: one work-item per vertex, heights
// (unnormalised) in metres of x = i·cell, y = j·cell. The arithmetic is cl/terrain_noise_core.cl's.
__kernel void terrain_noise(__global float* height, const int nx, const int ny, const float cell,
                            const int family, const int octaves, const int cosine, const int by_height,
                            const float frequency, const float lacunarity, const float gain, const float offset,
                            const float extent_x, const uint seed_lo, const uint seed_hi,
                            const __global float* amplitudes) {
  const int k = get_global_id(0);
  if (k >= nx * ny) return;
  const int j = k / nx, i = k - j * nx;
  NoiseParams p;
  p.family = family;
  p.octaves = octaves;
  p.cosine = cosine;
  p.by_height = by_height;
  p.frequency = frequency;
  p.lacunarity = lacunarity;
  p.gain = gain;
  p.offset = offset;
  p.extent_x = extent_x;
  p.seed_lo = seed_lo;
  p.seed_hi = seed_hi;
  height[k] = noise_family_height(&p, (float)i * cell, (float)j * cell, amplitudes);
}
