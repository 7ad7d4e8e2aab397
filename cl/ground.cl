// SPDX-License-Identifier: MIT
// The layer stack after a step (docs/layers.md). Per vertex: the net change d of the step's
// fixed-point height goes to the loose sediment first (d > 0 adds to it; d < 0 takes min(s, −d)
// from it and the rest from the rock), so the rock surface r = h − s only ever falls. Then the
// exposed material: the sediment where s > 0, else the stratum whose band holds r (the number of
// contacts 1..L at or above r; the bedrock below the last), and its factors for the models:
// erodibility × the hardness mask (0 where frozen), and the talus threshold (quanta per cell).
// Materials: 0..L−1 the strata top first, L the bedrock, L+1 the sediment.

__kernel void ground_update(const __global long* height, __global long* previous, __global long* sediment,
                            const __global long* contacts, const int strata, const int n,
                            const __global float* mask, const __global float* material_erodibility,
                            const __global float* material_talus, __global float* erodibility,
                            __global float* talus, __global int* exposed) {
  const int k = get_global_id(0);
  if (k >= n) return;
  const long h = height[k], d = h - previous[k];
  const long s = d > 0 ? sediment[k] + d : max(sediment[k] + d, 0L);
  previous[k] = h;
  sediment[k] = s;
  const long rock = h - s;
  int e = 0;
  for (int l = 0; l < strata; ++l) e += rock <= contacts[l * n + k] ? 1 : 0;  // contact l + 1
  e = s > 0 ? strata + 1 : e;
  erodibility[k] = material_erodibility[e] * mask[k];
  talus[k] = material_talus[e];
  exposed[k] = e;
}
