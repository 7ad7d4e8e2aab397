// SPDX-License-Identifier: MIT
// Spatial hash: linear cell keys (x fastest, so a row of cells is one run of particles), a stable
// LSD radix sort (digits of `bits` bits, at most RADIX_MAX_BITS: host -D), the reordering of the
// particle arrays, the cell start/end tables and the tiles of the neighbour passes (physics.md §2,
// "Neighbour search").
//
// Determinism: the sort splits the particles into contiguous chunks (a few long ones on a CPU,
// thousands of short ones on a GPU). Each chunk's digit histogram, one exclusive scan in (digit,
// chunk) order, then each chunk scatters its elements in order. No atomics: the permutation is a
// pure function of the keys (a stable sort has one result, however the chunks are cut).

#define RADIX_MAX (1u << RADIX_MAX_BITS)

// A key's digit in a pass: its `bits` bits from `shift` (both sorts, here and radix_tiles.cl).
inline uint radix_digit(uint key, uint shift, uint bits) { return (key >> shift) & ((1u << bits) - 1u); }

// key: the linear index of the particle's cell; dead particles get dead_key (> every live key) so the
// sort moves them to the end, where they are dropped.
// First it empties the cells the previous sort occupied (sorted_key, sorted_n: that sort's keys),
// so that the table is reset at the cost of the particles, not of the grid (which covers the whole
// terrain), in the same launch. sorted_key may be `key` itself: work-item i reads its own old key
// before it writes the new one, and touches no other.
__kernel void hash_keys(const __global float* x, const __global float* y, const __global float* z,
                        const __global uint* id, __global uint* key, __global uint* index, const uint n,
                        const float ox, const float oy, const float oz, const float inv_cell, const int gx,
                        const int gy, const int gz, const uint dead_key, const __global uint* sorted_key,
                        const uint sorted_n, __global uint* cell_start) {
  const uint i = get_global_id(0);
  if (i < sorted_n) {
    const uint old = sorted_key[i];
    if (old != dead_key) cell_start[old] = EMPTY_CELL;
  }
  if (i >= n) return;
  const Grid g = make_grid(ox, oy, oz, inv_cell, gx, gy, gz);
  key[i] = (id[i] & DEAD_FLAG) ? dead_key : linear_cell(cell_of((float3)(x[i], y[i], z[i]), g), g);
  index[i] = i;
}

// hist[digit * blocks + block] = how many keys of the block's chunk have that digit (the key's
// `bits` bits from `shift`).
__kernel void radix_histogram(const __global uint* key, const uint n, const uint shift, const uint bits,
                              const uint chunk, __global uint* hist) {
  const uint block = get_global_id(0);
  const uint blocks = get_global_size(0);
  const uint radix = 1u << bits;
  uint counts[RADIX_MAX];
  for (uint d = 0; d < radix; ++d) counts[d] = 0;
  const uint begin = block * chunk;
  const uint end = min(begin + chunk, n);
  for (uint i = begin; i < end; ++i) counts[radix_digit(key[i], shift, bits)]++;
  for (uint d = 0; d < radix; ++d) hist[d * blocks + block] = counts[d];
}

// The histogram's exclusive prefix sum, in (digit, block) order: where each block's keys of each
// digit go. On a CPU one work-item walks the table (one work-group in all).
__kernel void radix_scan(__global uint* hist, const uint count, __local uint* sums) {
  group_exclusive_scan(hist, hist, count, sums);
}

// The same scan on a wide device, over many work-groups: a GPU's thousands of sort blocks make a
// histogram of a million counts, which one work-group takes milliseconds to walk. Group g owns the
// slice [g·per, (g + 1)·per): scan_slice_totals sums each slice, scan_totals scans the sums (one
// work-group), scan_slices scans each slice from its sum's prefix, a round of the group's size at
// a time. Every load is coalesced (consecutive work-items, consecutive counts). Integer sums: the
// same prefixes as the serial scan.
__kernel void scan_slice_totals(const __global uint* data, const uint count, const uint per, __global uint* totals,
                                __local uint* sums) {
  const uint item = get_local_id(0), items = get_local_size(0);
  const uint begin = get_group_id(0) * per, end = min(begin + per, count);
  uint total = 0;
  for (uint k = begin + item; k < end; k += items) total += data[k];
  group_inclusive_sum(total, sums);
  if (item == 0) totals[get_group_id(0)] = sums[items - 1];
}

__kernel void scan_totals(__global uint* totals, const uint groups, __local uint* sums) {
  group_exclusive_scan(totals, totals, groups, sums);
}

__kernel void scan_slices(__global uint* data, const uint count, const uint per, const __global uint* totals,
                          __local uint* sums) {
  const uint item = get_local_id(0), items = get_local_size(0);
  const uint begin = get_group_id(0) * per, end = min(begin + per, count);
  uint carry = totals[get_group_id(0)];
  for (uint base = begin; base < end; base += items) {
    const uint k = base + item;
    const uint own = k < end ? data[k] : 0;
    const uint through = group_inclusive_sum(own, sums);
    if (k < end) data[k] = carry + through - own;
    carry += sums[items - 1];
    barrier(CLK_LOCAL_MEM_FENCE);  // every work-item has read the round's total
  }
}

__kernel void radix_scatter(const __global uint* key_in, const __global uint* value_in, __global uint* key_out,
                            __global uint* value_out, const __global uint* hist, const uint n, const uint shift,
                            const uint bits, const uint chunk) {
  const uint block = get_global_id(0);
  const uint blocks = get_global_size(0);
  const uint radix = 1u << bits;
  uint offset[RADIX_MAX];
  for (uint d = 0; d < radix; ++d) offset[d] = hist[d * blocks + block];
  const uint begin = block * chunk;
  const uint end = min(begin + chunk, n);
  for (uint i = begin; i < end; ++i) {
    const uint k = key_in[i];
    const uint pos = offset[radix_digit(k, shift, bits)]++;
    key_out[pos] = k;
    value_out[pos] = value_in[i];
  }
}

// Gathers fields into sorted order, as 4-byte words (bit-exact for floats and integers alike),
// seven at a time (the store lends its free buffers during the sort): one launch moves what seven
// would, and on a CPU device each launch costs a wake-up of every worker thread.
__kernel void reorder_words(const __global uint* perm, const uint n, const __global uint* in0, __global uint* out0,
                            const __global uint* in1, __global uint* out1, const __global uint* in2,
                            __global uint* out2, const __global uint* in3, __global uint* out3,
                            const __global uint* in4, __global uint* out4, const __global uint* in5,
                            __global uint* out5, const __global uint* in6, __global uint* out6) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const uint from = perm[i];
  out0[i] = in0[from];
  out1[i] = in1[from];
  out2[i] = in2[from];
  out3[i] = in3[from];
  out4[i] = in4[from];
  out5[i] = in5[from];
  out6[i] = in6[from];
}

// After sorting: the first and one-past-last sorted index of every occupied cell (empty cells hold
// EMPTY_CELL in cell_start), and the number of live particles (dead ones sort to the end).
__kernel void cell_bounds(const __global uint* key, const uint n, const uint dead_key, __global uint* cell_start,
                          __global uint* cell_end, __global uint* alive) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const uint k = key[i];
  if (k == dead_key) {
    if (i == 0) alive[0] = 0;
    return;
  }
  if (i + 1 == n || key[i + 1] == dead_key) alive[0] = i + 1;
  if (i == 0 || key[i - 1] != k) cell_start[k] = i;
  if (i + 1 == n || key[i + 1] != k) cell_end[k] = i + 1;
}

// The neighbour sets the hash yields (for tests and debugging): for each particle, the ids of every
// other particle within `radius`, up to max_neighbours, and their count.
__kernel void neighbour_list(const __global float* x, const __global float* y, const __global float* z,
                             const __global uint* id, const uint n, const float ox, const float oy, const float oz,
                             const float inv_cell, const int gx, const int gy, const int gz,
                             const __global uint* cell_start, const __global uint* cell_end, const float radius,
                             const uint max_neighbours, __global uint* count, __global uint* neighbours) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const Grid grid = make_grid(ox, oy, oz, inv_cell, gx, gy, gz);
  const float3 pi = (float3)(x[i], y[i], z[i]);
  uint found = 0;
  NEIGHBOUR_ROWS_BEGIN(pi, grid, cell_start, cell_end)
  if (j != i) {
    const float3 d = pi - (float3)(x[j], y[j], z[j]);
    if (dot(d, d) < radius * radius) {
      if (found < max_neighbours) neighbours[i * max_neighbours + found] = id[j];
      ++found;
    }
  }
  NEIGHBOUR_ROWS_END
  count[i] = found;
}

// Tiles: each occupied cell's particles in runs of at most `tile` (a cell of 40 particles is tiles
// of 32 and 8). A neighbour pass runs one work-group per tile; the tile's particles share the cell
// and so the candidates, which the group loads once into local memory. Tiles of at most `small`
// particles (sheets of water one or two particles deep) are listed after the others, so that they
// run in work-groups of `small` work-items: an idle work-item still costs its turn on a CPU. Tiles
// of at most `lone` particles (a film: a drop to a cell) come last: for them the group's loading
// and barriers cost more than their few candidates, and a pass takes them one work-item a tile
// (the passes' _direct kernels, sph_boundary.cl).
// The list is a compaction of the particles that start a tile, in sorted order: per-chunk counts,
// one scan, per-chunk writes, as in the radix sort (no atomics, one result).
inline uint tile_size_at(const __global uint* key, const __global uint* cell_start, const __global uint* cell_end,
                         uint i, uint tile) {
  const uint first = cell_start[key[i]];
  if ((i - first) % tile != 0) return 0;  // not the start of a tile
  return min(tile, cell_end[key[i]] - i);
}

// A tile's class: 0 large, 1 small, 2 lone; 3 for a particle that starts no tile.
inline uint tile_class(uint size, uint small, uint lone) {
  return size == 0 ? 3u : size <= lone ? 2u : size <= small ? 1u : 0u;
}

// counts[c·blocks + block]: the chunk's tiles of class c.
__kernel void tile_count(const __global uint* key, const __global uint* cell_start, const __global uint* cell_end,
                         const __global uint* alive, const uint chunk, const uint tile, const uint small,
                         const uint lone, __global uint* counts) {
  const uint block = get_global_id(0);
  const uint blocks = get_global_size(0);
  const uint end = min((block + 1) * chunk, alive[0]);
  uint count[3] = {0, 0, 0};
  for (uint i = block * chunk; i < end; ++i) {
    const uint c = tile_class(tile_size_at(key, cell_start, cell_end, i, tile), small, lone);
    if (c < 3) ++count[c];
  }
  for (uint c = 0; c < 3; ++c) counts[c * blocks + block] = count[c];
}

// Exclusive scan of the 3·blocks counts in place: the large tiles first, then the small ones, then
// the lone ones. The totals go to summary[1] (large), summary[2] (small) and summary[3] (lone);
// summary[0] is the live count, so the host reads them all at once.
__kernel void tile_scan(__global uint* counts, const uint blocks, __global uint* summary, __local uint* sums) {
  const uint total = group_exclusive_scan(counts, counts, 3 * blocks, sums);
  barrier(CLK_GLOBAL_MEM_FENCE);  // every work-item's prefixes written
  if (get_local_id(0) == 0) {
    const uint large = counts[blocks], large_and_small = counts[2 * blocks];
    summary[1] = large;
    summary[2] = large_and_small - large;
    summary[3] = total - large_and_small;
  }
}

__kernel void tile_scatter(const __global uint* key, const __global uint* cell_start, const __global uint* cell_end,
                           const __global uint* alive, const uint chunk, const uint tile, const uint small,
                           const uint lone, const __global uint* counts, __global uint* tile_first) {
  const uint block = get_global_id(0);
  const uint blocks = get_global_size(0);
  const uint end = min((block + 1) * chunk, alive[0]);
  uint out[3] = {counts[block], counts[blocks + block], counts[2 * blocks + block]};
  for (uint i = block * chunk; i < end; ++i) {
    const uint c = tile_class(tile_size_at(key, cell_start, cell_end, i, tile), small, lone);
    if (c < 3) tile_first[out[c]++] = i;
  }
}
