// SPDX-License-Identifier: MIT
#include "runnel/sph/spatial_hash.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/compute/launch.hpp"
#include "runnel/core/error.hpp"

namespace runnel {
namespace {

constexpr int kMaxCellsPerAxis =
    1024;  // 2^30 cells at most: a linear key (and the dead key) fits 31 bits

const std::vector<std::string> kHashSources = {"cl/common.cl", "cl/grid.cl", "cl/spatial_hash.cl",
                                               "cl/radix_tiles.cl"};
// cl/radix_tiles.cl's work-group and tile.
constexpr std::size_t kRadixGroup = 256, kRadixTile = 1024;

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
  int bits = 1;
  while ((std::size_t{1} << bits) <= cell_count()) ++bits;  // the dead key is cell_count()
  return bits;
}

SpatialHash::SpatialHash(ComputeContext& compute, const GridSpec& grid, std::uint32_t tile)
    : compute_(compute), grid_(grid), tile_(tile > 0 ? tile : device_tile(compute)) {
  dead_key_ = static_cast<std::uint32_t>(grid.cell_count());  // one past every live cell
  cl::Program& program = compute.program(
      kHashSources, "-DRADIX_MAX_BITS=" + std::to_string(kMaxDigitBits) +
                        " -DRADIX_TILE_MAX_BITS=" + std::to_string(kMaxTileDigitBits));
  hash_keys_ = Kernel(compute, program, "hash_keys");
  histogram_ = Kernel(compute, program, "radix_histogram");
  scan_ = Kernel(compute, program, "radix_scan");
  scan_slice_totals_ = Kernel(compute, program, "scan_slice_totals");
  scan_totals_ = Kernel(compute, program, "scan_totals");
  scan_slices_ = Kernel(compute, program, "scan_slices");
  scatter_ = Kernel(compute, program, "radix_scatter");
  sort_tiles_ = Kernel(compute, program, "radix_sort_tiles");
  scatter_tiles_ = Kernel(compute, program, "radix_scatter_tiles");
  reorder_ = Kernel(compute, program, "reorder_words");
  cell_bounds_ = Kernel(compute, program, "cell_bounds");
  neighbour_list_ = Kernel(compute, program, "neighbour_list");
  tile_count_ = Kernel(compute, program, "tile_count");
  tile_scan_ = Kernel(compute, program, "tile_scan");
  tile_scatter_ = Kernel(compute, program, "tile_scatter");
  auto& ctx = compute.context();
  // The sort's chunks (and the tile compaction's): a CPU's threads each walk a few long runs, a
  // GPU wants thousands of short ones in flight; the histogram scans run over many work-groups
  // there, the tile scan in one as wide as the device allows.
  least_chunk_ = compute.wide() ? 32 : 512;
  most_blocks_ = compute.wide() ? 4096 : 256;
  scan_group_ =
      compute.wide() ? std::min<std::size_t>({1024, scan_.max_group(), tile_scan_.max_group()}) : 1;
  sort_in_tiles_ = compute.wide() && sort_tiles_.max_group() >= kRadixGroup &&
                   scatter_tiles_.max_group() >= kRadixGroup;
  const int most_digit_bits = sort_in_tiles_ ? kMaxTileDigitBits : kMaxDigitBits;
  passes_ = (grid.key_bits() + most_digit_bits - 1) / most_digit_bits;
  digit_bits_ = (grid.key_bits() + passes_ - 1) / passes_;
  // A digit's counts a block, or the tiles' three classes a block (build_tiles).
  hist_ = cl::Buffer(ctx, CL_MEM_READ_WRITE,
                     std::max<std::size_t>(radix(), 3) * most_blocks_ * sizeof(cl_uint));
  if (compute.wide()) {
    slice_group_ =
        std::min<std::size_t>({256, scan_slice_totals_.max_group(), scan_slices_.max_group()});
    slice_totals_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, scan_group_ * sizeof(cl_uint));
  }
  summary_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, 4 * sizeof(cl_uint));
  cell_start_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, grid.cell_count() * sizeof(cl_uint));
  cell_end_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, grid.cell_count() * sizeof(cl_uint));
  // Once: afterwards each build empties only the cells its predecessor filled.
  compute.queue().enqueueFillBuffer(cell_start_, kEmptyCell, 0,
                                    grid.cell_count() * sizeof(cl_uint));
}

std::uint32_t SpatialHash::device_tile(const ComputeContext& compute) {
  return compute.wide() ? 1 : kDefaultTile;
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

void SpatialHash::launch_tiled(Kernel& tiled, Kernel& direct) const {
  for (Kernel* k : {&tiled, &direct}) bind_cells(k->set("tile_first", tile_first_));
  tiled.set("tile_offset", cl_uint{0}).launch_groups(tiles_, tile_);
  tiled.set("tile_offset", tiles_).launch_groups(small_tiles_, kSmallTile);
  direct.set("tile_offset", tiles_ + small_tiles_).set("tiles", lone_tiles_).set("tile", tile_);
  if (lone_tiles_ > 0) direct.launch(round_up_work(lone_tiles_));
}

void SpatialHash::scan_histogram(const cl::Buffer& hist, cl_uint count) {
  if (slice_group_ == 0) {
    scan_.set("hist", hist).set("count", count);
    scan_.set("sums", cl::Local((scan_group_ + 1) * sizeof(cl_uint))).launch_groups(1, scan_group_);
    return;
  }
  // Slices of at least four rounds of the group, and at most as many as one group scans the
  // totals of. All three kernels are timed as radix_scan, the one they stand for.
  const SerialRuns slices = serial_runs(count, 4 * slice_group_, scan_group_);
  const cl_uint groups = static_cast<cl_uint>(slices.runs),
                per = static_cast<cl_uint>(slices.length);
  const cl::LocalSpaceArg slice_sums = cl::Local(slice_group_ * sizeof(cl_uint));
  scan_slice_totals_.set("data", hist).set("count", count).set("per", per);
  scan_slice_totals_.set("totals", slice_totals_).set("sums", slice_sums);
  scan_slice_totals_.launch_groups(groups, slice_group_, "radix_scan");
  scan_totals_.set("totals", slice_totals_).set("groups", groups);
  scan_totals_.set("sums", cl::Local((scan_group_ + 1) * sizeof(cl_uint)));
  scan_totals_.launch_groups(1, scan_group_, "radix_scan");
  scan_slices_.set("data", hist).set("count", count).set("per", per);
  scan_slices_.set("totals", slice_totals_).set("sums", slice_sums);
  scan_slices_.launch_groups(groups, slice_group_, "radix_scan");
}

void SpatialHash::ensure_capacity(std::size_t n) {
  if (n <= capacity_) return;
  capacity_ = std::max(n, capacity_ + capacity_ / 2);
  const cl::Buffer last_sort = keys_[sorted_in_];
  for (int b = 0; b < 2; ++b) {
    keys_[b] = cl::Buffer(compute_.context(), CL_MEM_READ_WRITE, capacity_ * sizeof(cl_uint));
    values_[b] = cl::Buffer(compute_.context(), CL_MEM_READ_WRITE, capacity_ * sizeof(cl_uint));
  }
  // The last sort's keys move along: the next hash_keys empties their cells.
  if (sorted_ > 0)
    compute_.queue().enqueueCopyBuffer(last_sort, keys_[sorted_in_], 0, 0,
                                       sorted_ * sizeof(cl_uint));
}

void SpatialHash::build(ParticleStore& store) {
  begin_build(store);
  finish_build(store);
}

void SpatialHash::begin_build(ParticleStore& store) {
  const cl_uint n = static_cast<cl_uint>(store.size());
  auto& q = compute_.queue();
  summary_pending_ = false;
  if (n == 0 && sorted_ == 0) return;
  ensure_capacity(n);  // with n = 0, the last sort's keys are there already

  // 1. Keys: the linear index of each particle's cell; and the cells of the last sort emptied.
  store.bind(hash_keys_, {kX, kY, kZ, kId});
  bind_grid(hash_keys_);
  hash_keys_.set("key", keys_[0]).set("index", values_[0]).set("dead_key", dead_key_);
  hash_keys_.set("sorted_key", keys_[sorted_in_]).set("sorted_n", sorted_);
  hash_keys_.set("cell_start", cell_start_).launch(round_up_work(std::max(n, sorted_)));
  sorted_ = 0;
  if (n == 0) return;

  // 2. Stable LSD radix sort of (key, index), radix_digit_bits() a pass: on a CPU in serial runs,
  // on a GPU in tiles sorted by work-groups. The runs' count follows n (at least least_chunk_ keys
  // each, at most most_blocks_; the tile list below is cut the same way): a handful of particles
  // must not pay for many histograms. The permutation depends on neither (a stable sort has one
  // result).
  const SerialRuns runs = serial_runs(n, least_chunk_, most_blocks_);
  const cl_uint blocks = static_cast<cl_uint>(runs.runs), chunk = static_cast<cl_uint>(runs.length);
  const int in = sort_in_tiles_ ? sort_in_tiles(n, store) : sort_in_runs(n, blocks, chunk);

  // 3. Gather every persistent field (and the water depth, when it is carried) into the sorted
  // order (as 4-byte words: bit-exact for floats too), up to seven fields a launch through the
  // store's free buffers, in as few launches as that allows (12 fields: two of six; 13 with the
  // depth: seven and six). A group's unused slots repeat its last field (the same word written
  // twice by the same work-item).
  constexpr int kSlots = 7;
  static constexpr const char* kIn[kSlots] = {"in0", "in1", "in2", "in3", "in4", "in5", "in6"};
  static constexpr const char* kOut[kSlots] = {"out0", "out1", "out2", "out3",
                                               "out4", "out5", "out6"};
  static_assert(kSlots <= ParticleStore::kTemporaryCount);
  std::vector<ParticleField> carried;
  for (int k = 0; k < kPersistentFieldCount; ++k) carried.push_back(static_cast<ParticleField>(k));
  if (carry_depth_) carried.push_back(kDepth);
  carried.insert(carried.end(), carried_fields_.begin(), carried_fields_.end());
  const int fields = static_cast<int>(carried.size());
  const int launches = (fields + kSlots - 1) / kSlots;
  const int per_launch = (fields + launches - 1) / launches;
  auto field = [&carried](int k) { return carried[static_cast<std::size_t>(k)]; };
  for (int first = 0; first < fields; first += per_launch) {
    const int end = std::min(first + per_launch, fields);
    reorder_.set("perm", values_[in]).set("n", n);
    for (int g = 0; g < kSlots; ++g) {
      const int k = std::min(first + g, end - 1);
      reorder_.set(kIn[g], store.buffer(field(k)));
      reorder_.set(kOut[g], store.temporary(k - first));
    }
    reorder_.launch(round_up_work(n), "reorder");
    for (int k = first; k < end; ++k) store.adopt_temporary(field(k), k - first);
  }

  // 4. Cell ranges and the live count (dead particles sorted to the end).
  cell_bounds_.set("key", keys_[in]).set("n", n).set("dead_key", dead_key_);
  cell_bounds_.set("cell_start", cell_start_).set("cell_end", cell_end_).set("alive", summary_);
  cell_bounds_.launch(round_up_work(n));
  sorted_ = n;
  sorted_in_ = in;

  // 5. Tiles of each cell's particles, for the neighbour passes' work-groups. The chunk counts go
  // where the sort's histogram was, the tile list where its spare permutation was. Tiles of one
  // particle (a GPU's passes) make every live particle a lone tile of its own: that list would be
  // the identity, so it is not built (the direct kernels take tile t as particle t).
  tile_first_ = values_[1 - in];
  per_particle_ = tile_ == 1 && lone_ >= 1;
  if (!per_particle_) build_tiles(in, blocks, chunk);
  q.enqueueReadBuffer(summary_, CL_FALSE, 0, sizeof(summary_host_), summary_host_, nullptr,
                      &summary_read_);
  summary_pending_ = true;
}

int SpatialHash::sort_in_runs(cl_uint n, cl_uint blocks, cl_uint chunk) {
  int in = 0;
  for (int pass = 0; pass < passes_; ++pass) {
    const cl_uint shift = digit_bits_ * pass, bits = digit_bits_;
    histogram_.set("key", keys_[in]).set("n", n).set("shift", shift).set("bits", bits);
    histogram_.set("chunk", chunk).set("hist", hist_).launch(blocks);
    scan_histogram(hist_, radix() * blocks);
    scatter_.set("key_in", keys_[in]).set("value_in", values_[in]);
    scatter_.set("key_out", keys_[1 - in]).set("value_out", values_[1 - in]);
    scatter_.set("hist", hist_).set("n", n).set("shift", shift).set("bits", bits);
    scatter_.set("chunk", chunk);
    scatter_.launch(blocks);
    in = 1 - in;
  }
  return in;
}

// Each pass sorts the tiles of keys_[0] into keys_[1] and scatters them back: the result stays in
// keys_[0]. The tiles' counts (radix() a tile) go in a spare buffer of the store (free until the
// gather), so the sort needs no memory of its own that grows with the particles; a store of a few
// hundred particles, too small for them, lends hist_ instead.
int SpatialHash::sort_in_tiles(cl_uint n, ParticleStore& store) {
  const cl_uint tiles = static_cast<cl_uint>((n + kRadixTile - 1) / kRadixTile);
  const cl::Buffer& hist = store.capacity() >= radix() * tiles ? store.temporary(0) : hist_;
  for (int pass = 0; pass < passes_; ++pass) {
    const cl_uint shift = digit_bits_ * pass, bits = digit_bits_;
    for (Kernel* k : {&sort_tiles_, &scatter_tiles_})
      k->set("hist", hist).set("n", n).set("shift", shift).set("bits", bits);
    sort_tiles_.set("key_in", keys_[0]).set("value_in", values_[0]);
    sort_tiles_.set("key_out", keys_[1]).set("value_out", values_[1]);
    sort_tiles_.launch_groups(tiles, kRadixGroup);
    scan_histogram(hist, radix() * tiles);
    scatter_tiles_.set("key_in", keys_[1]).set("value_in", values_[1]);
    scatter_tiles_.set("key_out", keys_[0]).set("value_out", values_[0]);
    scatter_tiles_.launch_groups(tiles, kRadixGroup);
  }
  return 0;
}

void SpatialHash::build_tiles(int in, cl_uint blocks, cl_uint chunk) {
  for (Kernel* k : {&tile_count_, &tile_scatter_}) {
    k->set("key", keys_[in]).set("cell_start", cell_start_).set("cell_end", cell_end_);
    k->set("alive", summary_).set("chunk", chunk).set("tile", tile_).set("small", kSmallTile);
    k->set("lone", lone_);
    k->set("counts", hist_);
  }
  tile_count_.launch(blocks);
  const cl::LocalSpaceArg scan_sums = cl::Local((scan_group_ + 1) * sizeof(cl_uint));
  tile_scan_.set("counts", hist_)
      .set("blocks", blocks)
      .set("summary", summary_)
      .set("sums", scan_sums);
  tile_scan_.launch_groups(1, scan_group_);
  tile_scatter_.set("tile_first", tile_first_).launch(blocks);
}

void SpatialHash::finish_build(ParticleStore& store) {
  tiles_ = small_tiles_ = lone_tiles_ = 0;
  if (!summary_pending_) return;  // nothing was sorted: no particles
  summary_read_.wait();
  summary_pending_ = false;
  store.truncate(summary_host_[0]);
  if (per_particle_) {
    lone_tiles_ = summary_host_[0];
    return;
  }
  tiles_ = summary_host_[1];
  small_tiles_ = summary_host_[2];
  lone_tiles_ = summary_host_[3];
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
