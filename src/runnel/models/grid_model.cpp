// SPDX-License-Identifier: MIT
#include "runnel/models/grid_model.hpp"

#include <numeric>

#include "runnel/core/error.hpp"
#include "runnel/core/scenario.hpp"
#include "runnel/core/version.hpp"

namespace runnel {

GridModel::GridModel(ComputeContext& compute, const Parameters& params, const Heightmap& terrain)
    : compute_(compute),
      params_(params),
      state_(compute, terrain, params.real("erosion.height_quantum")),
      ground_(make_ground(compute, params, state_.terrain(), state_.initial_terrain(),
                          state_.initial_fixed())),
      placeholder_(placeholder_buffer(compute)) {
  const std::vector<float> weights = rain_weights(params, terrain.nx, terrain.ny);  // read once
  rain_weight_ = rain_weight_buffer(compute, params, weights);
  for (float w : weights) rained_vertices_ += w;
}

double GridModel::step() {
  const double dt = take_step();
  if (ground_) ground_->update();
  time_ += dt;
  ++steps_;
  return dt;
}

Heightmap GridModel::terrain() {
  Heightmap t = state_.terrain().download();
  t.origin_x = state_.initial_terrain().origin_x;
  t.origin_z = state_.initial_terrain().origin_z;
  t.georef = state_.initial_terrain().georef;
  return t;
}

long long GridModel::suspended_quanta() {
  if (!state_.has(kSedimentSuspended)) return 0;
  const auto s = state_.download_int64(kSedimentSuspended);
  return std::accumulate(s.begin(), s.end(), 0LL);
}

double GridModel::water_volume() {
  double depth = 0;
  for (float d : state_.download_float(kSurfaceWaterDepth)) depth += d;
  const double cell = state_.terrain().cell();
  return depth * cell * cell;
}

MassBalance GridModel::mass_balance() {
  return mass_balance_of(state_.initial_fixed(), state_.terrain().download_fixed(),
                         suspended_quanta(), outflow_quanta(), lost_quanta(),
                         state_.terrain().volume_quantum(), uplift_quanta());
}

std::string GridModel::status() {
  return info().name + " model";
}

CheckpointData GridModel::checkpoint() {
  CheckpointData d;
  d.model = info().name;
  d.runnel_version = kVersion;
  d.source_revision = kRevision;
  d.parameters_toml = parameters_toml(params_);
  d.terrain = terrain();
  d.height_quantum = state_.terrain().quantum();
  d.height_fixed = state_.terrain().download_fixed();
  d.initial_fixed = state_.initial_fixed();
  d.time = time_;
  d.dt = next_dt();
  d.steps = steps_;
  d.seed = params_.integer("run.seed");
  d.fields = state_.download();
  if (ground_)
    for (StoredField& f : ground_->fields()) d.fields.push_back(std::move(f));
  d.model_counters = counters();
  return d;
}

void GridModel::restore(const CheckpointData& d) {
  if (d.model != info().name)
    throw input_error("checkpoint: it holds the " + d.model + " model, not " + info().name);
  if (d.terrain.nx != state_.initial_terrain().nx || d.terrain.ny != state_.initial_terrain().ny)
    throw input_error("checkpoint: terrain size does not match the model");
  state_.set_initial_fixed(d.initial_fixed);
  state_.terrain().upload_fixed(d.height_fixed);
  state_.upload(without_ground_fields(d.fields));
  if (ground_) ground_->restore(d.fields);
  restore_counters(d.model_counters);
  time_ = d.time;
  steps_ = d.steps;
  restore_next_dt(d.dt);
}

std::int64_t counter_value(const std::vector<std::pair<std::string, std::int64_t>>& counters,
                           const std::string& name) {
  for (auto& [key, value] : counters)
    if (key == name) return value;
  throw input_error("checkpoint: counter " + name + " is missing");
}

}  // namespace runnel
