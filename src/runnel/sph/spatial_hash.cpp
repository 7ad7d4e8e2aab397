// SPDX-License-Identifier: MIT
#include "runnel/sph/spatial_hash.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/compute/launch.hpp"
#include "runnel/core/error.hpp"

namespace runnel {
namespace {

constexpr int kMaxCellsPerAxis = 1024;  // 10 Morton bits per axis

const std::vector<std::string> kHashSources = {"cl/common.cl", "cl/grid.cl", "cl/spatial_hash.cl"};

}  // namespace

GridSpec GridSpec::covering(const double lo[3], const double hi[3], double cell) {
  GridSpec g;
  g.cell = static_cast<float>(cell);
  for (int a = 0; a < 3; ++a) {
    g.origin[a] = static_cast<float>(lo[a]);
    const double cells = std::ceil((hi[a] - lo[a]) / cell);
    if (!(cells < kMaxCellsPerAxis + 0.5)) {
      throw input_error("the fluid domain needs " + std::to_string(static_cast<long long>(cells)) +
                        " hash cells along axis " + std::to_string(a) + " (at most " +
                        std::to_string(kMaxCellsPerAxis) + "): increase sph.spacing");
    }
    g.dims[a] = std::max(1, static_cast<int>(cells));
  }
  return g;
}

int GridSpec::key_bits() const {
  int bits = 0;
  while ((1 << bits) < std::max({dims[0], dims[1], dims[2]})) ++bits;
  return 3 * bits + 1;
}

SpatialHash::SpatialHash(ComputeContext& compute, const GridSpec& grid)
    : compute_(compute), grid_(grid) {
  const int bits = grid.key_bits();
  dead_key_ = 1u << (bits - 1);  // one past every Morton code of the grid
  passes_ = (bits + 7) / 8;
  cl::Program& program = compute.program(kHashSources);
  hash_keys_ = cl::Kernel(program, "hash_keys");
  histogram_ = cl::Kernel(program, "radix_histogram");
  scan_ = cl::Kernel(program, "radix_scan");
  scatter_ = cl::Kernel(program, "radix_scatter");
  reorder_ = cl::Kernel(program, "reorder_words");
  cell_bounds_ = cl::Kernel(program, "cell_bounds");
  neighbour_list_ = cl::Kernel(program, "neighbour_list");
  auto& ctx = compute.context();
  hist_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, 256 * kRadixBlocks * sizeof(cl_uint));
  alive_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, sizeof(cl_uint));
  cell_start_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, grid.cell_count() * sizeof(cl_uint));
  cell_end_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, grid.cell_count() * sizeof(cl_uint));
}

void SpatialHash::set_grid_args(cl::Kernel& k, cl_uint i) const {
  k.setArg(i + 0, grid_.origin[0]);
  k.setArg(i + 1, grid_.origin[1]);
  k.setArg(i + 2, grid_.origin[2]);
  k.setArg(i + 3, 1.0f / grid_.cell);
  k.setArg(i + 4, grid_.dims[0]);
  k.setArg(i + 5, grid_.dims[1]);
  k.setArg(i + 6, grid_.dims[2]);
}

void SpatialHash::ensure_capacity(std::size_t n) {
  if (n <= capacity_) return;
  capacity_ = std::max(n, capacity_ + capacity_ / 2);
  for (int b = 0; b < 2; ++b) {
    keys_[b] = cl::Buffer(compute_.context(), CL_MEM_READ_WRITE, capacity_ * sizeof(cl_uint));
    values_[b] = cl::Buffer(compute_.context(), CL_MEM_READ_WRITE, capacity_ * sizeof(cl_uint));
  }
}

void SpatialHash::build(ParticleStore& store) {
  const cl_uint n = static_cast<cl_uint>(store.size());
  auto& q = compute_.queue();
  auto& prof = compute_.profiler();
  const cl_uint empty = 0xFFFFFFFFu;
  q.enqueueFillBuffer(cell_start_, empty, 0, grid_.cell_count() * sizeof(cl_uint));
  if (n == 0) return;
  ensure_capacity(n);

  // 1. Keys: the Morton code of each particle's cell.
  hash_keys_.setArg(0, store.buffer(kX));
  hash_keys_.setArg(1, store.buffer(kY));
  hash_keys_.setArg(2, store.buffer(kZ));
  hash_keys_.setArg(3, store.buffer(kId));
  hash_keys_.setArg(4, keys_[0]);
  hash_keys_.setArg(5, values_[0]);
  hash_keys_.setArg(6, n);
  set_grid_args(hash_keys_, 7);
  hash_keys_.setArg(14, dead_key_);
  prof.launch(hash_keys_, round_up_work(n), "hash_keys");

  // 2. Stable LSD radix sort of (key, index), 8 bits per pass. The blocks' count follows n (about
  // 512 keys each, at most kRadixBlocks): a handful of particles must not pay for 256 histograms.
  // The permutation does not depend on it (a stable sort has one result).
  const cl_uint blocks = std::clamp<cl_uint>((n + 511) / 512, 1, kRadixBlocks);
  const cl_uint chunk = (n + blocks - 1) / blocks;
  int in = 0;
  for (int pass = 0; pass < passes_; ++pass) {
    const cl_uint shift = 8 * pass;
    set_args(histogram_, keys_[in], n, shift, chunk, hist_);
    prof.launch(histogram_, blocks, "radix_histogram");
    set_args(scan_, hist_, static_cast<cl_uint>(256 * blocks));
    prof.launch(scan_, 1, "radix_scan");
    set_args(scatter_, keys_[in], values_[in], keys_[1 - in], values_[1 - in], hist_, n, shift,
             chunk);
    prof.launch(scatter_, blocks, "radix_scatter");
    in = 1 - in;
  }

  // 3. Gather every persistent field into the sorted order (as 4-byte words: bit-exact for floats
  // too).
  for (int f = 0; f < kPersistentFieldCount; ++f) {
    set_args(reorder_, values_[in], store.buffer(static_cast<ParticleField>(f)),
             store.scratch(static_cast<ParticleField>(f)), n);
    prof.launch(reorder_, round_up_work(n), "reorder");
  }
  store.swap_scratch();

  // 4. Cell ranges and the live count (dead particles sorted to the end).
  cell_bounds_.setArg(0, keys_[in]);
  cell_bounds_.setArg(1, store.buffer(kX));
  cell_bounds_.setArg(2, store.buffer(kY));
  cell_bounds_.setArg(3, store.buffer(kZ));
  cell_bounds_.setArg(4, n);
  set_grid_args(cell_bounds_, 5);
  cell_bounds_.setArg(12, dead_key_);
  cell_bounds_.setArg(13, cell_start_);
  cell_bounds_.setArg(14, cell_end_);
  cell_bounds_.setArg(15, alive_);
  prof.launch(cell_bounds_, round_up_work(n), "cell_bounds");
  cl_uint alive = 0;
  q.enqueueReadBuffer(alive_, CL_TRUE, 0, sizeof(cl_uint), &alive);
  store.truncate(alive);
}

std::vector<std::vector<std::uint32_t>> SpatialHash::neighbour_lists(ParticleStore& store,
                                                                     float radius) {
  const cl_uint n = static_cast<cl_uint>(store.size());
  const cl_uint max_neighbours = 512;
  std::vector<std::vector<std::uint32_t>> lists(n);
  if (n == 0) return lists;
  cl::Buffer count(compute_.context(), CL_MEM_READ_WRITE, n * sizeof(cl_uint));
  cl::Buffer ids(compute_.context(), CL_MEM_READ_WRITE,
                 static_cast<std::size_t>(n) * max_neighbours * sizeof(cl_uint));
  auto& k = neighbour_list_;
  k.setArg(0, store.buffer(kX));
  k.setArg(1, store.buffer(kY));
  k.setArg(2, store.buffer(kZ));
  k.setArg(3, store.buffer(kId));
  k.setArg(4, n);
  set_grid_args(k, 5);
  k.setArg(12, cell_start_);
  k.setArg(13, cell_end_);
  k.setArg(14, radius);
  k.setArg(15, max_neighbours);
  k.setArg(16, count);
  k.setArg(17, ids);
  compute_.profiler().launch(k, round_up_work(n), "neighbour_list");
  std::vector<cl_uint> counts(n), all(static_cast<std::size_t>(n) * max_neighbours);
  compute_.queue().enqueueReadBuffer(count, CL_TRUE, 0, n * sizeof(cl_uint), counts.data());
  compute_.queue().enqueueReadBuffer(ids, CL_TRUE, 0, all.size() * sizeof(cl_uint), all.data());
  for (cl_uint i = 0; i < n; ++i) {
    if (counts[i] > max_neighbours) throw runtime_error("neighbour_list: more than 512 neighbours");
    lists[i].assign(all.begin() + static_cast<std::size_t>(i) * max_neighbours,
                    all.begin() + static_cast<std::size_t>(i) * max_neighbours + counts[i]);
  }
  return lists;
}

}  // namespace runnel
