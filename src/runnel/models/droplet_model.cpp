// SPDX-License-Identifier: MIT
#include "runnel/models/droplet_model.hpp"

#include "runnel/ground/ground_settings.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/compute/buffer_bytes.hpp"
#include "runnel/compute/build_options.hpp"
#include "runnel/compute/launch.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/parameter_groups.hpp"
#include "runnel/core/settings_table.hpp"
#include "runnel/core/text.hpp"
#include "runnel/models/memory_check.hpp"

namespace runnel {

namespace {

// droplet_bin's one work-group (DROPLET_BIN_GROUP).
constexpr std::size_t kBinGroup = 64;

// clang-format off
const SettingsTable<DropletSettings> kDropletTable = {
      // droplet: Beyer 2015's particle droplets (models.md), in cells and metres of height
      {"droplet.radius", "3", "cells", 0.5, 8, {}, "erosion brush radius (its weights are kept in private memory: at most 8)", &DropletSettings::radius, "DROPLET_RADIUS"},
      {"droplet.inertia", "0.05", "1", 0, 1, {}, "how much a droplet keeps its direction", &DropletSettings::inertia, "DROPLET_INERTIA"},
      {"droplet.capacity", "4", "1", 0, 1e6, {}, "capacity factor: capacity = −Δh · speed · water · factor", &DropletSettings::capacity, "DROPLET_CAPACITY"},
      {"droplet.min_capacity", "0.01", "m", 0, 1e6, {}, "smallest capacity", &DropletSettings::min_capacity, "DROPLET_MIN_CAPACITY"},
      {"droplet.erode", "0.3", "1", 0, 1, {}, "fraction of the free capacity eroded per step", &DropletSettings::erode, "DROPLET_ERODE"},
      {"droplet.deposit", "0.3", "1", 0, 1, {}, "fraction of the excess load deposited per step", &DropletSettings::deposit, "DROPLET_DEPOSIT"},
      {"droplet.evaporate", "0.01", "1", 0, 1, {}, "fraction of the water evaporating per step", &DropletSettings::evaporate, "DROPLET_EVAPORATE"},
      {"droplet.gravity", "4", "1", 0, 1e3, {}, "gravity of the speed update", &DropletSettings::gravity, "DROPLET_GRAVITY"},
      {"droplet.lifetime", "30", "steps", 1, 100000, {}, "steps a droplet lives", &DropletSettings::lifetime, "DROPLET_LIFETIME"},
      {"droplet.initial_water", "1", "1", 0, 1e6, {}, "water a droplet starts with", &DropletSettings::initial_water, "DROPLET_INITIAL_WATER"},
      {"droplet.initial_speed", "1", "1", 0, 1e6, {}, "speed a droplet starts with", &DropletSettings::initial_speed, "DROPLET_INITIAL_SPEED"},
      {"droplet.batch", "0", "droplets", 0, 1e8, {}, "droplets per parallel batch (they move in lockstep, each step on the terrain the last step left); 0: one per 64 cells, so few share a pit; at most one per 4 vertices (more dig the pits they gather in without bound)", &DropletSettings::batch},
      {"droplet.volume", "0", "m^3", 0, 1e9, {}, "rain water one droplet stands for (rain_volume in metrics; runnel compare sets it to the SPH particle volume); 0: cell³", &DropletSettings::volume},
};
// clang-format on

}  // namespace

std::vector<ParamSpec> droplet_parameters() {
  return settings_specs(kDropletTable);
}

DropletSettings DropletSettings::from(const Parameters& p) {
  return read_settings(p, kDropletTable);
}

std::string DropletSettings::build_options() const {
  // The brush's extent in whole cells sizes its private weight array.
  return settings_defines(*this, kDropletTable) +
         " -DDROPLET_RADIUS_CELLS=" + std::to_string(static_cast<int>(std::ceil(radius))) +
         " -DDROPLET_BIN_GROUP=" + std::to_string(kBinGroup);
}

const ModelInfo& DropletModel::model_info() {
  static const ModelInfo info{"droplet",
                              "Erosion_Beyer2015",
                              "H. Beyer: Implementation of a method for hydraulic erosion, "
                              "Bachelor's thesis, TU Munich, 2015",
                              "droplet",
                              ModelClock::kIterations,
                              true,
                              {{kTopographicElevation, FieldIntent::kInOut}},
                              {},
                              40};
  return info;
}

namespace {

// Fields of a droplet's state: x, z, dir_x, dir_z, speed, water (droplet.cl's DROPLET_X ..).
constexpr std::size_t kDropletFields = 6;

// The bytes of a batch's droplet state (kDropletFields planes of `stride` floats, the batch padded
// to whole vectors), refused with the key's name when one device buffer cannot hold them.
// Bytes a droplet of a batch takes: on the device its state, load and plan (about 72), and on the
// host the ordering by place (about 32).
constexpr double kBytesPerBatchDroplet = 104;
// Vertices a droplet of a batch at least: the droplets move in lockstep without seeing each other's
// changes, and at one droplet for two vertices the ones gathering in a pit dig it without bound
// until the balance breaks (measured on 257 x 257 fBm and plane terrains; one for 64, the default,
// and one for 4 keep it exact).
constexpr long long kLeastVerticesPerDroplet = 4;

std::size_t state_bytes(const ComputeContext& compute, long long batch, long long stride,
                        long long vertices) {
  if (batch > std::max(vertices / kLeastVerticesPerDroplet, 1LL))
    throw input_error("droplet.batch: " + std::to_string(batch) + " droplets on " +
                      std::to_string(vertices) + " vertices; at most one for " +
                      std::to_string(kLeastVerticesPerDroplet) +
                      " vertices (a batch moves in lockstep, each droplet blind to the others)");
  const MemoryRoom room = memory_room();
  const double need = static_cast<double>(batch) * kBytesPerBatchDroplet;
  if (room.bytes > 0 && need > room.bytes)
    throw input_error("droplet.batch: " + std::to_string(batch) + " droplets need about " +
                      format_number(need / 1e9) + " GB; " + room.limited_by + " leaves " +
                      format_number(room.bytes / 1e9) + " GB");
  const double bytes = static_cast<double>(stride) * kDropletFields * sizeof(float);
  if (bytes > static_cast<double>(compute.info().max_alloc)) {
    throw input_error("droplet.batch: " + std::to_string(batch) + " droplets need " +
                      format_number(bytes / 1e6) + " MB in one device buffer; " +
                      compute.info().name + " allows " +
                      format_number(static_cast<double>(compute.info().max_alloc) / 1e6) + " MB");
  }
  return static_cast<std::size_t>(bytes);
}

cl::Program& droplet_program(ComputeContext& compute, const DropletSettings& settings,
                             const DropletBlocks& blocks, const Parameters& params) {
  return compute.program({"cl/common.cl", "cl/models/droplet.cl"},
                         settings.build_options() + ground_defines(params) +
                             " -DDROPLET_BLOCK_ROWS=" + std::to_string(blocks.rows) +
                             " -DDROPLET_BLOCK_WIDTH=" + std::to_string(blocks.width));
}

}  // namespace

DropletModel::DropletModel(ComputeContext& compute, const Parameters& params,
                           const Heightmap& terrain)
    : DropletModel(
          compute, params, terrain,
          DropletBlocks::layout(terrain.nx, terrain.ny, DropletSettings::from(params).radius,
                                compute.info().compute_units)) {}

DropletModel::DropletModel(ComputeContext& compute, const Parameters& params,
                           const Heightmap& terrain, const DropletBlocks& blocks)
    : GridModel(compute, params, terrain),
      settings_(DropletSettings::from(params)),
      seed_(static_cast<std::uint64_t>(params.integer("run.seed"))),
      blocks_(blocks),
      spawn_kernel_(compute, droplet_program(compute, settings_, blocks_, params), "droplet_spawn"),
      move_kernel_(compute, droplet_program(compute, settings_, blocks_, params), "droplet_move"),
      bin_kernel_(compute, droplet_program(compute, settings_, blocks_, params), "droplet_bin"),
      apply_kernel_(compute, droplet_program(compute, settings_, blocks_, params), "droplet_apply"),
      counters_(compute.context(), CL_MEM_READ_WRITE, 3 * sizeof(cl_long)),
      droplet_state_(compute.context(), CL_MEM_READ_WRITE,
                     state_bytes(compute, batch_size(), plane_stride(),
                                 static_cast<long long>(state_.vertices()))),
      droplet_load_(compute.context(), CL_MEM_READ_WRITE,
                    static_cast<std::size_t>(plane_stride()) * sizeof(cl_long)),
      plan_place_(compute.context(), CL_MEM_READ_WRITE,
                  static_cast<std::size_t>(plane_stride()) * 2 * sizeof(cl_float)),
      plan_(compute.context(), CL_MEM_READ_WRITE,
            static_cast<std::size_t>(plane_stride()) * 2 * sizeof(cl_long)),
      plan_bin_(compute.context(), CL_MEM_READ_WRITE,
                static_cast<std::size_t>(plane_stride()) * 2 * sizeof(cl_uint)),
      block_count_(compute.context(), CL_MEM_READ_WRITE, blocks_.count() * sizeof(cl_uint)),
      block_start_(compute.context(), CL_MEM_READ_WRITE, blocks_.count() * sizeof(cl_uint)),
      block_list_(compute.context(), CL_MEM_READ_WRITE,
                  static_cast<std::size_t>(plane_stride()) * sizeof(cl_uint)) {
  const int least = DropletBlocks::rows_for(settings_.radius);
  if (blocks_.rows < least || blocks_.width < least ||
      blocks_.blocks_x * blocks_.width < terrain.nx || blocks_.blocks_y * blocks_.rows < terrain.ny)
    throw runtime_error("droplet blocks of " + std::to_string(blocks_.rows) + " × " +
                        std::to_string(blocks_.width) +
                        " cells would let droplet_apply's work-items " +
                        "share a vertex or miss a droplet (at least " + std::to_string(least) +
                        " each way, covering the map)");
  compute.queue().enqueueFillBuffer(block_count_, cl_uint{0}, 0, blocks_.count() * sizeof(cl_uint));
  compute.queue().enqueueFillBuffer(counters_, cl_long{0}, 0, 3 * sizeof(cl_long));
  const cl::Buffer& erodibility = bed() ? bed()->erodibility : placeholder_;
  const auto stride = static_cast<cl_uint>(plane_stride());
  move_kernel_.set("erodibility", erodibility)
      .set("stride", stride)
      .set("state", droplet_state_)
      .set("load", droplet_load_)
      .set("counters", counters_)
      .set("plan_place", plan_place_)
      .set("plan", plan_)
      .set("plan_bin", plan_bin_)
      .set("block_count", block_count_)
      .set("blocks_x", blocks_.blocks_x);
  bin_kernel_.set("blocks", static_cast<cl_uint>(blocks_.count()))
      .set("block_count", block_count_)
      .set("block_start", block_start_)
      .set("stride", stride)
      .set("plan_bin", plan_bin_)
      .set("block_list", block_list_);
  apply_kernel_.set("erodibility", erodibility)
      .set("stride", stride)
      .set("state", droplet_state_)
      .set("plan_place", plan_place_)
      .set("plan", plan_)
      .set("block_start", block_start_)
      .set("block_count", block_count_)
      .set("block_list", block_list_)
      .set("blocks_x", blocks_.blocks_x)
      .set("blocks_y", blocks_.blocks_y);
  spawn_kernel_.set("rain_weight", rain_weight());
}

double DropletModel::scratch_bytes() const {
  return buffer_bytes({&counters_, &droplet_state_, &droplet_load_, &plan_place_, &plan_,
                       &plan_bin_, &block_count_, &block_start_, &block_list_});
}

long long DropletModel::plane_stride() const {
  return (batch_size() + kMostLanes - 1) / kMostLanes * kMostLanes;
}

long long DropletSettings::batch_for(long long vertices) const {
  // Droplets of one batch do not see each other's changes: many ending in the same pit would all
  // fill it. One droplet per 64 cells by default keeps that rare.
  return batch > 0 ? batch : std::max<long long>(1, vertices / 64);
}

long long DropletModel::batch_size() const {
  return settings_.batch_for(static_cast<long long>(state_.vertices()));
}

double DropletModel::droplet_volume() const {
  const double cell = state_.initial_terrain().cell;
  return settings_.volume > 0 ? settings_.volume : cell * cell * cell;
}

double DropletModel::take_step() {
  if (rain_on() > 0) run_batch(static_cast<cl_uint>(batch_size()), 0, 0, 0);
  return 1.0;
}

// Painted rain: droplets of droplet_volume() each on every disc, as many as its water makes over
// the step (the fraction carried to the next), in batches of at most batch_size().
void DropletModel::paint(double dt) {
  const double cell = state_.initial_terrain().cell;
  for (const RainDisc& disc : painted()) {
    if (disc.rate <= 0) continue;  // a sink: droplets have no standing water to drain
    paint_carry_ += disc.rate * dt * M_PI * disc.radius * disc.radius / droplet_volume();
    auto count = static_cast<long long>(std::floor(paint_carry_));
    paint_carry_ -= static_cast<double>(count);
    for (; count > 0; count -= batch_size()) {
      run_batch(static_cast<cl_uint>(std::min(count, batch_size())),
                static_cast<float>(disc.x / cell), static_cast<float>(disc.z / cell),
                static_cast<float>(std::max(disc.radius / cell, 1e-3)));
    }
  }
}

// One batch of `count` droplets; spawn_radius > 0 (cells) rains them on a disc instead of the map.
void DropletModel::run_batch(cl_uint count, float spawn_x, float spawn_z, float spawn_radius) {
  if (count == 0) return;
  DeviceTerrain& terrain = state_.terrain();
  spawn_kernel_.set("nx", terrain.nx())
      .set("ny", terrain.ny())
      .set("seed", static_cast<cl_ulong>(seed_))
      .set("first_droplet", static_cast<cl_ulong>(droplets_))
      .set("count", count)
      .set("stride", static_cast<cl_uint>(plane_stride()))
      .set("state", droplet_state_)
      .set("load", droplet_load_)
      .set("counters", counters_)
      .set("spawn_x", spawn_x)
      .set("spawn_z", spawn_z)
      .set("spawn_radius", spawn_radius)
      .launch(round_up_work(count));
  order_by_place(count);
  // The batch moves in lockstep, each step on the terrain the previous one left (droplet.cl). The
  // droplets read the fixed heights, so the float view is refreshed once, after the batch.
  move_kernel_.set("height_fixed", terrain.height_fixed())
      .set("nx", terrain.nx())
      .set("ny", terrain.ny())
      .set("quantum", static_cast<float>(terrain.quantum()))
      .set("count", count);
  bin_kernel_.set("count", count);
  terrain.bind_fixed_changes(apply_kernel_);
  apply_kernel_.set("nx", terrain.nx()).set("ny", terrain.ny());
  const std::size_t group = std::min(blocks_.group, apply_kernel_.max_group());
  for (int step = 0; step < settings_.lifetime; ++step) {
    move_kernel_.set("step_index", static_cast<cl_int>(step)).launch_lanes(count);
    bin_kernel_.launch_groups(1, kBinGroup);
    for (cl_int parity = 0; parity < 4; ++parity) {
      if (blocks_.has_parity(parity))
        apply_kernel_.set("parity", parity)
            .launch_groups((blocks_.per_parity() + group - 1) / group, group);
    }
  }
  terrain.view_changed();
  droplets_ += count;
}

// Stores a batch's droplets in the order of the vertex they fell on, row by row (ties in droplet
// order), so that neighbouring work-items of droplet_move and droplet_apply share rows of the
// terrain in the cache and read their states in sequence. The result does not depend on the order
// (droplet.cl), since a droplet's number matters only to droplet_spawn's random numbers; the speed
// does: random places miss the cache at every brush vertex.
void DropletModel::order_by_place(cl_uint count) {
  const auto stride = static_cast<std::size_t>(plane_stride());  // one plane per field (droplet.cl)
  std::vector<cl_float> state(kDropletFields * stride);
  compute_.queue().enqueueReadBuffer(droplet_state_, CL_TRUE, 0, state.size() * sizeof(cl_float),
                                     state.data());
  const auto nx = static_cast<std::uint64_t>(state_.terrain().nx());
  std::vector<std::uint64_t> keyed(count);  // vertex index << 32 | droplet
  for (cl_uint d = 0; d < count; ++d) {
    const auto i = static_cast<std::uint64_t>(state[d]),  // x, then z: the first two planes
        j = static_cast<std::uint64_t>(state[stride + d]);
    keyed[d] = (j * nx + i) << 32 | d;
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<cl_float> ordered(state.size());
  for (std::size_t field = 0; field < kDropletFields; ++field) {
    for (cl_uint g = 0; g < count; ++g)
      ordered[field * stride + g] = state[field * stride + (keyed[g] & 0xffffffffu)];
  }
  compute_.queue().enqueueWriteBuffer(droplet_state_, CL_TRUE, 0, ordered.size() * sizeof(cl_float),
                                      ordered.data());
}

std::array<cl_long, 3> DropletModel::read_counters() {
  std::array<cl_long, 3> c{};
  compute_.queue().enqueueReadBuffer(counters_, CL_TRUE, 0, sizeof(c), c.data());
  return c;
}

long long DropletModel::outflow_quanta() {
  return read_counters()[1];
}

long long DropletModel::droplets_out() {
  return read_counters()[0];
}

long long DropletModel::droplets_fallen() {
  return static_cast<long long>(droplets_) - read_counters()[2];
}

std::vector<std::pair<std::string, std::int64_t>> DropletModel::counters() {
  return {{"droplets", static_cast<std::int64_t>(droplets_)},
          {"droplets_out", droplets_out()},
          {"outflow_quanta", outflow_quanta()},
          {"droplets_masked", read_counters()[2]}};
}

namespace {
// Checkpoints from before rain masks have no droplets_masked: none were.
std::int64_t masked_counter(const std::vector<std::pair<std::string, std::int64_t>>& c) {
  for (auto& [key, value] : c)
    if (key == "droplets_masked") return value;
  return 0;
}
}  // namespace

void DropletModel::restore_counters(const std::vector<std::pair<std::string, std::int64_t>>& c) {
  droplets_ = static_cast<std::uint64_t>(counter_value(c, "droplets"));
  const cl_long device[3] = {counter_value(c, "droplets_out"), counter_value(c, "outflow_quanta"),
                             masked_counter(c)};
  compute_.queue().enqueueWriteBuffer(counters_, CL_TRUE, 0, sizeof(device), device);
}

JsonObject DropletModel::diagnostics() {
  return JsonObject()
      .add("droplets", static_cast<long long>(droplets_))
      .add("droplets_out", droplets_out())
      .add("droplets_fallen", droplets_fallen())
      .add("droplets_per_batch", batch_size())
      .add("droplet_volume_m3", droplet_volume());
}

}  // namespace runnel
