// SPDX-License-Identifier: MIT
// The spatial hash's radix sort on a wide device (a GPU): one pass of `bits` bits, in tiles of
// RADIX_TILE keys that a work-group of RADIX_GROUP work-items sorts in local memory (Satish, Harris &
// Garland 2009). radix_sort_tiles sorts each tile by the pass's digit, stably, with a one-bit
// split a bit, writes the sorted tile back and the tile's digit counts into hist[digit·tiles + tile];
// the counts are scanned as the serial sort's are (spatial_hash.cl); radix_scatter_tiles moves
// each key of a sorted tile to its digit's offset plus its rank in the tile's run of that digit.
// Consecutive keys of a run go to consecutive addresses, so the writes coalesce; the CPU's sort
// (spatial_hash.cl), one work-item walking a long block, writes one key at a time wherever its
// digit points. No atomics: the permutation is the stable sort's, the same bits as the CPU's.
// Compile-time constants (host -D): RADIX_TILE_MAX_BITS, the widest digit a pass takes here.

#define RADIX_TILE_MAX (1u << RADIX_TILE_MAX_BITS)

#define RADIX_GROUP 256
#define RADIX_PER_ITEM 4
#define RADIX_TILE (RADIX_GROUP * RADIX_PER_ITEM)
#define RADIX_ABSENT 0xFFFFFFFFu

// Where each digit's run starts in a tile sorted by it (RADIX_ABSENT for a digit it lacks) and,
// where `end` is not null, where it ends; from the keys in local memory, `valid` keys, the rest
// padding.
inline void digit_runs(const __local uint* keys, uint valid, uint shift, uint bits, __local uint* start,
                       __local uint* end) {
  const uint item = get_local_id(0);
  for (uint d = item; d < (1u << bits); d += RADIX_GROUP) start[d] = RADIX_ABSENT;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint p = item; p < valid; p += RADIX_GROUP) {
    const uint d = radix_digit(keys[p], shift, bits);
    if (p == 0 || radix_digit(keys[p - 1], shift, bits) != d) start[d] = p;
    if (end && (p + 1 == valid || radix_digit(keys[p + 1], shift, bits) != d)) end[d] = p + 1;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
}

__kernel void radix_sort_tiles(const __global uint* key_in, const __global uint* value_in, __global uint* key_out,
                               __global uint* value_out, __global uint* hist, const uint n, const uint shift,
                               const uint bits) {
  __local uint keys[RADIX_TILE], values[RADIX_TILE], sums[RADIX_GROUP], start[RADIX_TILE_MAX], end[RADIX_TILE_MAX];
  const uint item = get_local_id(0), tile = get_group_id(0), tiles = get_num_groups(0);
  const uint base = tile * RADIX_TILE, valid = min((uint)RADIX_TILE, n - base);
  // Padding has every bit set: the pass's last digit, after every real key of that digit (the sort is
  // stable and the padding comes last), so it fills the tile's end and is never written out.
  for (uint p = item; p < RADIX_TILE; p += RADIX_GROUP) {
    keys[p] = p < valid ? key_in[base + p] : 0xFFFFFFFFu;
    values[p] = p < valid ? value_in[base + p] : 0;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint bit = shift; bit < shift + bits; ++bit) {
    // A stable split on one bit: keys with 0 first, in order, then those with 1. Work-item q holds
    // the tile's keys RADIX_PER_ITEM·q ... in order.
    uint k[RADIX_PER_ITEM], v[RADIX_PER_ITEM], zeros = 0;
    for (uint r = 0; r < RADIX_PER_ITEM; ++r) {
      k[r] = keys[item * RADIX_PER_ITEM + r];
      v[r] = values[item * RADIX_PER_ITEM + r];
      zeros += ((k[r] >> bit) & 1u) == 0u;
    }
    const uint zeros_through = group_inclusive_sum(zeros, sums);  // common.cl
    const uint all_zeros = sums[RADIX_GROUP - 1];
    uint zero_at = zeros_through - zeros;
    uint one_at = all_zeros + item * RADIX_PER_ITEM - zero_at;
    barrier(CLK_LOCAL_MEM_FENCE);  // every work-item has read its keys and the total
    for (uint r = 0; r < RADIX_PER_ITEM; ++r) {
      const uint to = ((k[r] >> bit) & 1u) == 0u ? zero_at++ : one_at++;
      keys[to] = k[r];
      values[to] = v[r];
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  digit_runs(keys, valid, shift, bits, start, end);
  for (uint d = item; d < (1u << bits); d += RADIX_GROUP) {
    hist[d * tiles + tile] = start[d] == RADIX_ABSENT ? 0 : end[d] - start[d];
  }
  for (uint p = item; p < valid; p += RADIX_GROUP) {
    key_out[base + p] = keys[p];
    value_out[base + p] = values[p];
  }
}

// Every key of the sorted tiles (key_in) to its place (key_out): hist holds, scanned, where each
// tile's run of each digit begins.
__kernel void radix_scatter_tiles(const __global uint* key_in, const __global uint* value_in, __global uint* key_out,
                                  __global uint* value_out, const __global uint* hist, const uint n,
                                  const uint shift, const uint bits) {
  __local uint keys[RADIX_TILE], start[RADIX_TILE_MAX], offset[RADIX_TILE_MAX];
  const uint item = get_local_id(0), tile = get_group_id(0), tiles = get_num_groups(0);
  const uint base = tile * RADIX_TILE, valid = min((uint)RADIX_TILE, n - base);
  for (uint p = item; p < valid; p += RADIX_GROUP) keys[p] = key_in[base + p];
  barrier(CLK_LOCAL_MEM_FENCE);
  digit_runs(keys, valid, shift, bits, start, 0);
  for (uint d = item; d < (1u << bits); d += RADIX_GROUP) {
    offset[d] = start[d] == RADIX_ABSENT ? 0 : hist[d * tiles + tile] - start[d];
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint p = item; p < valid; p += RADIX_GROUP) {
    const uint to = offset[radix_digit(keys[p], shift, bits)] + p;
    key_out[to] = keys[p];
    value_out[to] = value_in[base + p];
  }
}
