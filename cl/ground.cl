// SPDX-License-Identifier: MIT
// The layer stack after a step (docs/layers.md). Per vertex: the net change d of the step's
// fixed-point height goes to the loose sediment first (d > 0 adds to it; d < 0 takes min(s, −d)
// from it and the rest from the rock), so the rock surface r = h − s only ever falls. Then the
// rock's material, the stratum whose band holds r (the number of contacts 1..L at or above r; the
// bedrock below the last), and the factors the models read: the erodibility of the active layer
// (below) × the hardness mask (0 where frozen), and the exposed material's talus threshold (quanta).
// Materials: 0..L−1 the strata top first, L the bedrock, L+1 the sediment.

__kernel void ground_update(const __global long* height, __global long* previous, __global long* sediment,
                            const __global long* contacts, const int strata, const int n,
                            const __global float* mask, const __global float* material_erodibility,
                            const __global long* material_talus, const long active_layer,
                            __global float* erodibility, __global float* rock_erodibility,
                            __global float* sediment_erodibility, __global long* talus, __global int* exposed) {
  const int k = get_global_id(0);
  if (k >= n) return;
  const long h = height[k], d = h - previous[k];
  const long s = d > 0 ? sediment[k] + d : max(sediment[k] + d, 0L);
  previous[k] = h;
  sediment[k] = s;
  const long rock = h - s;
  int e = 0;
  for (int l = 0; l < strata; ++l) e += rock <= contacts[l * n + k] ? 1 : 0;  // contact l + 1
  // The particle models (sph, droplet) read the active layer's erodibility (Hirano 1971): a blend of
  // the sediment and the rock under it by the share of the active layer's thickness the sediment
  // fills, so a film of deposit does not make hard rock soft. The grid models take the sediment
  // first and then the rock, each at its own erodibility (bed_detachment in cl/common.cl). The map
  // shows the sediment where it fills half the active layer or more.
  const float cover = fmin((float)s / (float)active_layer, 1.0f);
  const int sediment_index = strata + 1;
  const float e_sediment = material_erodibility[sediment_index] * mask[k], e_rock = material_erodibility[e] * mask[k];
  erodibility[k] = cover * e_sediment + (1.0f - cover) * e_rock;
  rock_erodibility[k] = e_rock;
  sediment_erodibility[k] = e_sediment;
  const int shown = 2 * s >= active_layer ? sediment_index : e;
  talus[k] = material_talus[shown];
  exposed[k] = shown;
}
