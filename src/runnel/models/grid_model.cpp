// SPDX-License-Identifier: MIT
#include "runnel/models/grid_model.hpp"

#include <bit>
#include <cmath>
#include <numeric>

#include "runnel/compute/buffer_bytes.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/parameters_toml.hpp"
#include "runnel/core/version.hpp"
#include "runnel/ground/ground_settings.hpp"
#include "runnel/models/fields.hpp"
#include "runnel/terrain/standing_water.hpp"

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
  if (runnel::has_rain_mask(params)) rain_mask_ = RainMask(weights);
}

double GridModel::device_bytes() const {
  return state_.device_bytes() + buffer_bytes({&placeholder_, &rain_weight_}) +
         (ground_ ? ground_->device_bytes() : 0.0) + scratch_bytes();
}

double GridModel::step() {
  const double dt = take_step();
  if (!painted_.empty()) paint(dt);
  if (ground_) ground_->update();
  time_ += dt;
  if (global_rain_) rain_time_ += dt;
  ++steps_;
  // A model whose step reads nothing back never waits for the device, and an OpenCL queue keeps
  // every command it was given until someone waits: a coupling loop of millions of steps (Python,
  // BMI) would grow it until memory ran out. Waiting now and then bounds it at little cost.
  if (steps_ % kStepsBetweenWaits == 0) compute_.queue().finish();
  return dt;
}

bool GridModel::paints_rain() const {
  return state_.has(kSurfaceWaterDepth);
}

bool GridModel::set_global_rain(bool on) {
  if (!info().has_rain) return false;
  global_rain_ = on;
  return true;
}

// The painted depth goes straight into the water field, row band by row band: the host reads and
// writes only the rows a disc covers.
void GridModel::paint(double dt) {
  if (!paints_rain()) return;
  const int handle = state_.field(kSurfaceWaterDepth);
  const int nx = state_.terrain().nx(), ny = state_.terrain().ny();
  const double cell = state_.terrain().cell();
  for (const RainDisc& disc : painted_) {
    const std::vector<int> inside = vertices_in_disc(nx, ny, cell, disc);
    if (disc.rate < 0) drain(inside);
    if (inside.empty() || disc.rate <= 0) continue;
    const float depth = static_cast<float>(disc.rate * dt);
    const std::size_t first = static_cast<std::size_t>(inside.front() / nx) * nx,
                      last = static_cast<std::size_t>(inside.back() / nx + 1) * nx;
    std::vector<float> rows(last - first);
    cl::CommandQueue& queue = compute_.queue();
    queue.enqueueReadBuffer(state_.buffer(handle), CL_TRUE, first * sizeof(float),
                            rows.size() * sizeof(float), rows.data());
    for (int k : inside) rows[static_cast<std::size_t>(k) - first] += depth;
    queue.enqueueWriteBuffer(state_.buffer(handle), CL_TRUE, first * sizeof(float),
                             rows.size() * sizeof(float), rows.data());
    painted_volume_ +=
        static_cast<double>(depth) * cell * cell * static_cast<double>(inside.size());
  }
}

// A sink: the water on the vertices leaves the model; the sediment it held settles on them, so the
// volume of terrain and sediment stays exact.
void GridModel::drain(const std::vector<int>& vertices) {
  if (vertices.empty()) return;
  std::vector<float> depth = state_.download_float(kSurfaceWaterDepth);
  for (int k : vertices) depth[k] = 0.0f;
  state_.upload_field({kSurfaceWaterDepth, 1, depth, {}});
  if (!state_.has(kSedimentSuspended)) return;
  std::vector<std::int64_t> sediment = state_.download_int64(kSedimentSuspended);
  std::vector<std::int64_t> height = state_.terrain().download_fixed();
  for (int k : vertices) {
    height[k] += sediment[k];
    sediment[k] = 0;
  }
  state_.upload_field({kSedimentSuspended, 1, {}, sediment});
  state_.terrain().upload_fixed(height);
}

double GridModel::scenario_rain_volume() {
  const double cell = state_.terrain().cell();
  // The order of a run that never changes its mask: rate · Σw · cell · cell · time (+ 0).
  return scenario_rain_rate() * rained_vertices_ * cell * cell * (rain_time_ - rain_mark_) +
         rain_accum_;
}

bool GridModel::paint_rain_mask(const std::vector<int>& vertices, float value) {
  if (!rain_mask_.present()) return false;
  rain_accum_ = scenario_rain_volume();  // what fell under the old weights
  rain_mark_ = rain_time_;
  rain_mask_.paint(vertices, value);
  sync_rain_weights();
  return true;
}

void GridModel::sync_rain_weights() {
  const std::vector<float>& w = rain_mask_.weights();
  compute_.queue().enqueueWriteBuffer(rain_weight_, CL_TRUE, 0, w.size() * sizeof(float), w.data());
  rained_vertices_ = 0;
  for (float v : w) rained_vertices_ += v;
}

WaterView GridModel::water_view() {
  WaterView view;
  if (!state_.has(kSurfaceWaterDepth)) return view;
  view.depth = state_.download_float(kSurfaceWaterDepth);
  view.load.assign(view.depth.size(), 0.0f);
  view.speed.assign(view.depth.size(), 0.0f);
  if (state_.has(kSedimentSuspended)) {
    const auto s = state_.download_int64(kSedimentSuspended);
    const double q = state_.terrain().quantum();
    for (std::size_t k = 0; k < s.size(); ++k)
      if (view.depth[k] > 1e-6f) view.load[k] = static_cast<float>(s[k] * q / view.depth[k]);
  }
  if (state_.has(kSurfaceWaterVelocity)) {
    view.velocity = state_.download_float(kSurfaceWaterVelocity);  // interleaved (x, z)
    for (std::size_t k = 0; k < view.speed.size(); ++k)
      view.speed[k] = std::hypot(view.velocity[2 * k], view.velocity[2 * k + 1]);
  }
  return view;
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

bool GridModel::start_standing_water(const Parameters& params) {
  if (!has_standing_water(params)) return false;
  const std::vector<float> depth = initial_water_depth(params, state_.initial_terrain());
  state_.upload_field({kSurfaceWaterDepth, 1, depth, {}});
  initial_water_volume_ = runnel::water_volume(depth, state_.initial_terrain());
  return true;
}

std::optional<WaterBudget> GridModel::water_budget() {
  if (!state_.has(kSurfaceWaterDepth)) return std::nullopt;
  WaterBudget b;
  b.rain = rain_volume();
  b.stored = water_volume();
  b.per_edge = true;
  b.edges = edge_water_outflow();
  for (double v : b.edges) b.outflow += v;
  return b;
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
                         state_.terrain().volume_quantum(), uplift_quanta(), uplift_per_vertex(),
                         imposed_);
}

std::vector<double> GridModel::elevation() {
  return heights_in_metres(state_.terrain());
}

void GridModel::set_elevation(const std::vector<double>& metres) {
  imposed_.impose(state_.terrain(), metres, ground_ != nullptr);
}

void GridModel::set_rain_rates(const std::vector<float>& metres_per_second) {
  // The kernels read rain weights only when built with a mask (RAIN_MASK in cl/common.cl).
  if (rain_rate() > 0 && !rain_mask_.present())
    throw input_error("rain rates: the " + info().name + " model takes a rain field only when " +
                      "its scenario has a rain mask (ground.rain_mask)");
  rain_mask_.set(rain_weights_for(metres_per_second, rain_rate(), state_.vertices(), info().name));
  sync_rain_weights();
}

Heightmap GridModel::erosion_reference() {
  Heightmap reference = initial_terrain();
  const std::vector<std::int64_t> uplift = uplift_per_vertex();
  for (std::size_t k = 0; k < uplift.size(); ++k)
    reference.h[k] +=
        static_cast<float>(static_cast<double>(uplift[k]) * state_.terrain().quantum());
  imposed_.raise(reference, state_.terrain().quantum());
  return reference;
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
  rain_mask_.store(d.fields);
  imposed_.store(d.fields);
  store_own_fields(d.fields);
  d.model_counters = counters();
  // What painting (runnel-viewer) adds to the state; absent from every run without it.
  if (painted_volume_ != 0 || paint_carry_ != 0 || rain_time_ != time_ || rain_accum_ != 0 ||
      rain_mark_ != 0) {
    d.model_counters.emplace_back("painted_water_bits",
                                  std::bit_cast<std::int64_t>(painted_volume_));
    d.model_counters.emplace_back("paint_carry_bits", std::bit_cast<std::int64_t>(paint_carry_));
    d.model_counters.emplace_back("rain_time_bits", std::bit_cast<std::int64_t>(rain_time_));
    d.model_counters.emplace_back("rain_accum_bits", std::bit_cast<std::int64_t>(rain_accum_));
    d.model_counters.emplace_back("rain_mark_bits", std::bit_cast<std::int64_t>(rain_mark_));
  }
  return d;
}

void GridModel::restore(const CheckpointData& d) {
  if (d.model != info().name)
    throw input_error("checkpoint: it holds the " + d.model + " model, not " + info().name);
  if (d.terrain.nx != state_.initial_terrain().nx || d.terrain.ny != state_.initial_terrain().ny)
    throw input_error("checkpoint: terrain size does not match the model");
  state_.set_initial_fixed(d.initial_fixed);
  state_.terrain().upload_fixed(d.height_fixed);
  std::vector<StoredField> state_fields = without_ground_fields(d.fields);
  std::erase_if(state_fields, [](const StoredField& f) {
    return f.name == kImposedElevationChange || f.name.rfind("model__", 0) == 0;
  });
  state_.upload(state_fields);
  if (ground_) ground_->restore(d.fields);
  restore_counters(d.model_counters);
  time_ = d.time;
  steps_ = d.steps;
  restore_next_dt(d.dt);
  painted_volume_ = paint_carry_ = rain_accum_ = rain_mark_ = 0;
  rain_time_ = time_;
  for (auto& [key, value] : d.model_counters) {
    if (key == "painted_water_bits") painted_volume_ = std::bit_cast<double>(value);
    if (key == "paint_carry_bits") paint_carry_ = std::bit_cast<double>(value);
    if (key == "rain_time_bits") rain_time_ = std::bit_cast<double>(value);
    if (key == "rain_accum_bits") rain_accum_ = std::bit_cast<double>(value);
    if (key == "rain_mark_bits") rain_mark_ = std::bit_cast<double>(value);
  }
  rain_mask_.restore(d.fields);
  if (rain_mask_.present()) sync_rain_weights();
  imposed_.restore(d.fields);
  restore_own_fields(d.fields);
}

std::int64_t counter_value(const std::vector<std::pair<std::string, std::int64_t>>& counters,
                           const std::string& name) {
  for (auto& [key, value] : counters)
    if (key == name) return value;
  throw input_error("checkpoint: counter " + name + " is missing");
}

std::int64_t counter_value_or(const std::vector<std::pair<std::string, std::int64_t>>& counters,
                              const std::string& name, std::int64_t absent) {
  for (auto& [key, value] : counters)
    if (key == name) return value;
  return absent;
}

}  // namespace runnel
