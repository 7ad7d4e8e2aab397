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
  hash_keys_ = Kernel(compute, program, "hash_keys");
  histogram_ = Kernel(compute, program, "radix_histogram");
  scan_ = Kernel(compute, program, "radix_scan");
  scatter_ = Kernel(compute, program, "radix_scatter");
  reorder_ = Kernel(compute, program, "reorder_words");
  cell_bounds_ = Kernel(compute, program, "cell_bounds");
  neighbour_list_ = Kernel(compute, program, "neighbour_list");
  auto& ctx = compute.context();
  hist_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, 256 * kRadixBlocks * sizeof(cl_uint));
  alive_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, sizeof(cl_uint));
  cell_start_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, grid.cell_count() * sizeof(cl_uint));
  cell_end_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, grid.cell_count() * sizeof(cl_uint));
}

void SpatialHash::bind_grid(Kernel& k) const {
  k.set("ox", grid_.origin[0])
      .set("oy", grid_.origin[1])
      .set("oz", grid_.origin[2])
      .set("inv_cell", 1.0f / grid_.cell)
      .set("gx", grid_.dims[0])
      .set("gy", grid_.dims[1])
      .set("gz", grid_.dims[2]);
}

void SpatialHash::bind_cells(Kernel& k) const {
  bind_grid(k);
  k.set("cell_start", cell_start_).set("cell_end", cell_end_);
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
  const cl_uint empty = 0xFFFFFFFFu;
  q.enqueueFillBuffer(cell_start_, empty, 0, grid_.cell_count() * sizeof(cl_uint));
  if (n == 0) return;
  ensure_capacity(n);

  // 1. Keys: the Morton code of each particle's cell.
  store.bind(hash_keys_, {kX, kY, kZ, kId});
  bind_grid(hash_keys_);
  hash_keys_.set("key", keys_[0]).set("index", values_[0]).set("dead_key", dead_key_);
  hash_keys_.launch(round_up_work(n));

  // 2. Stable LSD radix sort of (key, index), 8 bits per pass. The blocks' count follows n (about
  // 512 keys each, at most kRadixBlocks): a handful of particles must not pay for 256 histograms.
  // The permutation does not depend on it (a stable sort has one result).
  const cl_uint blocks = std::clamp<cl_uint>((n + 511) / 512, 1, kRadixBlocks);
  const cl_uint chunk = (n + blocks - 1) / blocks;
  int in = 0;
  for (int pass = 0; pass < passes_; ++pass) {
    const cl_uint shift = 8 * pass;
    histogram_.set("key", keys_[in]).set("n", n).set("shift", shift).set("chunk", chunk);
    histogram_.set("hist", hist_).launch(blocks);
    scan_.set("hist", hist_).set("count", static_cast<cl_uint>(256 * blocks)).launch(1);
    scatter_.set("key_in", keys_[in]).set("value_in", values_[in]);
    scatter_.set("key_out", keys_[1 - in]).set("value_out", values_[1 - in]);
    scatter_.set("hist", hist_).set("n", n).set("shift", shift).set("chunk", chunk);
    scatter_.launch(blocks);
    in = 1 - in;
  }

  // 3. Gather every persistent field into the sorted order (as 4-byte words: bit-exact for floats
  // too).
  for (int f = 0; f < kPersistentFieldCount; ++f) {
    reorder_.set("perm", values_[in]).set("n", n);
    reorder_.set("in", store.buffer(static_cast<ParticleField>(f)));
    reorder_.set("out", store.scratch(static_cast<ParticleField>(f)));
    reorder_.launch(round_up_work(n), "reorder");
  }
  store.swap_scratch();

  // 4. Cell ranges and the live count (dead particles sorted to the end).
  store.bind(cell_bounds_, {kX, kY, kZ});
  bind_cells(cell_bounds_);
  cell_bounds_.set("key", keys_[in]).set("dead_key", dead_key_).set("alive", alive_);
  cell_bounds_.launch(round_up_work(n));
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
  store.bind(k, {kX, kY, kZ, kId});
  bind_cells(k);
  k.set("radius", radius).set("max_neighbours", max_neighbours);
  k.set("count", count).set("neighbours", ids).launch(round_up_work(n));
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
