// SPDX-License-Identifier: MIT
#include "runnel/models/droplet_model.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/compute/build_options.hpp"
#include "runnel/compute/launch.hpp"

namespace runnel {

DropletSettings DropletSettings::from(const Parameters& p) {
  DropletSettings s;
  s.radius = p.real("droplet.radius");
  s.inertia = p.real("droplet.inertia");
  s.capacity = p.real("droplet.capacity");
  s.min_capacity = p.real("droplet.min_capacity");
  s.erode = p.real("droplet.erode");
  s.deposit = p.real("droplet.deposit");
  s.evaporate = p.real("droplet.evaporate");
  s.gravity = p.real("droplet.gravity");
  s.lifetime = static_cast<int>(p.integer("droplet.lifetime"));
  s.initial_water = p.real("droplet.initial_water");
  s.initial_speed = p.real("droplet.initial_speed");
  s.batch = p.integer("droplet.batch");
  s.volume = p.real("droplet.volume");
  return s;
}

std::string DropletSettings::build_options() const {
  std::string o;
  o += float_define("DROPLET_RADIUS", radius);
  o += float_define("DROPLET_INERTIA", inertia);
  o += float_define("DROPLET_CAPACITY", capacity);
  o += float_define("DROPLET_MIN_CAPACITY", min_capacity);
  o += float_define("DROPLET_ERODE", erode);
  o += float_define("DROPLET_DEPOSIT", deposit);
  o += float_define("DROPLET_EVAPORATE", evaporate);
  o += float_define("DROPLET_GRAVITY", gravity);
  o += float_define("DROPLET_INITIAL_WATER", initial_water);
  o += float_define("DROPLET_INITIAL_SPEED", initial_speed);
  o += " -DDROPLET_LIFETIME=" + std::to_string(lifetime);
  o += " -DDROPLET_RADIUS_CELLS=" + std::to_string(static_cast<int>(std::ceil(radius)));
  return o;
}

const ModelInfo& DropletModel::model_info() {
  static const ModelInfo info{"droplet",
                              "Erosion_Beyer2015",
                              "H. Beyer: Implementation of a method for hydraulic erosion, "
                              "Bachelor's thesis, TU Munich, 2015",
                              "droplet",
                              ModelClock::kIterations,
                              true,
                              {{kTopographicElevation, FieldIntent::kInOut}}};
  return info;
}

DropletModel::DropletModel(ComputeContext& compute, const Parameters& params,
                           const Heightmap& terrain)
    : GridModel(compute, params, terrain),
      settings_(DropletSettings::from(params)),
      seed_(static_cast<std::uint64_t>(params.integer("run.seed"))),
      kernel_(compute,
              compute.program({"cl/common.cl", "cl/models/droplet.cl"}, settings_.build_options()),
              "droplet_step"),
      counters_(compute.context(), CL_MEM_READ_WRITE, 2 * sizeof(cl_long)),
      droplet_state_(compute.context(), CL_MEM_READ_WRITE,
                     static_cast<std::size_t>(batch_size()) * 6 * sizeof(float)),
      droplet_load_(compute.context(), CL_MEM_READ_WRITE,
                    static_cast<std::size_t>(batch_size()) * sizeof(cl_long)) {
  compute.queue().enqueueFillBuffer(counters_, cl_long{0}, 0, 2 * sizeof(cl_long));
}

long long DropletModel::batch_size() const {
  // Droplets of one batch do not see each other's changes: many ending in the same pit would all
  // fill it. One droplet per 64 cells by default keeps that rare.
  return settings_.batch > 0
             ? settings_.batch
             : std::max<long long>(1, static_cast<long long>(state_.vertices()) / 64);
}

double DropletModel::droplet_volume() const {
  const double cell = state_.initial_terrain().cell;
  return settings_.volume > 0 ? settings_.volume : cell * cell * cell;
}

double DropletModel::take_step() {
  DeviceTerrain& terrain = state_.terrain();
  const cl_uint count = static_cast<cl_uint>(batch_size());
  // The batch moves in lockstep, each step on the terrain the previous one left (droplet.cl).
  for (int step = 0; step < settings_.lifetime; ++step) {
    kernel_.set("height", terrain.height())
        .set("delta", terrain.delta())
        .set("nx", terrain.nx())
        .set("ny", terrain.ny())
        .set("quantum", static_cast<float>(terrain.quantum()))
        .set("seed", static_cast<cl_ulong>(seed_))
        .set("first_droplet", static_cast<cl_ulong>(droplets_))
        .set("count", count)
        .set("step_index", static_cast<cl_int>(step))
        .set("state", droplet_state_)
        .set("load", droplet_load_)
        .set("counters", counters_)
        .launch(round_up_work(count));
    terrain.apply();
  }
  droplets_ += count;
  return 1.0;
}

std::array<cl_long, 2> DropletModel::read_counters() {
  std::array<cl_long, 2> c{};
  compute_.queue().enqueueReadBuffer(counters_, CL_TRUE, 0, sizeof(c), c.data());
  return c;
}

long long DropletModel::outflow_quanta() {
  return read_counters()[1];
}

long long DropletModel::droplets_out() {
  return read_counters()[0];
}

std::vector<std::pair<std::string, std::int64_t>> DropletModel::counters() {
  return {{"droplets", static_cast<std::int64_t>(droplets_)},
          {"droplets_out", droplets_out()},
          {"outflow_quanta", outflow_quanta()}};
}

void DropletModel::restore_counters(const std::vector<std::pair<std::string, std::int64_t>>& c) {
  droplets_ = static_cast<std::uint64_t>(counter_value(c, "droplets"));
  const cl_long device[2] = {counter_value(c, "droplets_out"), counter_value(c, "outflow_quanta")};
  compute_.queue().enqueueWriteBuffer(counters_, CL_TRUE, 0, sizeof(device), device);
}

JsonObject DropletModel::diagnostics() {
  return JsonObject()
      .add("droplets", static_cast<long long>(droplets_))
      .add("droplets_out", droplets_out())
      .add("droplets_per_batch", batch_size())
      .add("droplet_volume_m3", droplet_volume());
}

}  // namespace runnel
