// SPDX-License-Identifier: MIT
#include "runnel/models/stream_power_model.hpp"

#include <cmath>

#include "runnel/core/error.hpp"
#include "runnel/core/parameter_groups.hpp"
#include "runnel/core/settings_table.hpp"
#include "runnel/landscape/flow_routing.hpp"
#include "runnel/landscape/stream_power.hpp"
#include "runnel/metrics/terrain_metrics.hpp"
#include "runnel/terrain/terrain_io.hpp"

namespace runnel {

namespace {
// The uplift of the steps shortened to land on a target, in checkpoints.
constexpr const char* kPartialUplift = "model__partial_uplift";
}  // namespace
namespace {

using S = StreamPowerSettings;
// clang-format off
const SettingsTable<StreamPowerSettings> kStreamPowerTable = {
      // stream_power: detachment-limited stream-power incision with uplift and hillslope diffusion (years)
      {"stream_power.k", "1e-5", "m^(1-2m)/yr", 0, 1e3, {}, "erodibility K of E = K A^m S^n", &S::k},
      {"stream_power.m", "0.5", "1", 0, 3, {}, "drainage-area exponent m", &S::m},
      {"stream_power.n", "1", "1", 0.1, 10, {}, "slope exponent n (n = 1: exact implicit step; otherwise Newton)", &S::n},
      {"stream_power.uplift", "1", "mm/yr", 0, 1e4, {}, "tectonic uplift rate U of every vertex but the edges (base level)", &S::uplift},
      {"stream_power.uplift_file", "\"\"", "", 0, 0, {}, "raster of U (mm/yr) per vertex, any terrain format, relative to the scenario; empty: stream_power.uplift everywhere", &S::uplift_file},
      {"stream_power.diffusivity", "0", "m^2/yr", 0, 1e6, {}, "linear hillslope diffusivity D; 0: none", &S::diffusivity},
      {"stream_power.dt", "1000", "yr", 1e-6, 1e9, {}, "years per step (the implicit incision is stable at any step)", &S::dt},
      {"stream_power.deposition", "0", "1", 0, 1e3, {}, "G of Davy & Lague 2009's erosion-deposition form: deposition G·Qs/A of the sediment flux Qs from upstream; 0: detachment-limited (all eroded material leaves)", &S::deposition},
      {"stream_power.base_level", "\"all\"", "", 0, 0, {"all", "west-east"}, "edges at base level (fixed, open): all four, or west and east only (north and south closed)", &S::base_level},
};
// clang-format on

}  // namespace

std::vector<ParamSpec> stream_power_parameters() {
  return settings_specs(kStreamPowerTable);
}

StreamPowerSettings StreamPowerSettings::from(const Parameters& p) {
  return read_settings(p, kStreamPowerTable);
}

const ModelInfo& StreamPowerModel::model_info() {
  static const ModelInfo info{
      "stream-power",
      "Erosion_BraunWillett2013",
      "J. Braun, S. D. Willett: A very efficient O(n), implicit and parallel method to solve the "
      "stream power equation governing fluvial incision and landscape evolution, Geomorphology "
      "180-181, 2013",
      "stream_power",
      ModelClock::kYears,
      false,
      {{kTopographicElevation, FieldIntent::kInOut}},
      {},
      40};
  return info;
}

StreamPowerModel::StreamPowerModel(ComputeContext& compute, const Parameters& params,
                                   const Heightmap& terrain)
    : GridModel(compute, params, terrain),
      settings_(StreamPowerSettings::from(params)),
      base_(settings_.base_level == "all" ? BaseLevel::kAllEdges : BaseLevel::kWestEast),
      router_(terrain.nx, terrain.ny, terrain.cell, base_) {
  const int nx = terrain.nx, ny = terrain.ny;
  if (nx < 3 || ny < 3)
    throw input_error(
        "terrain: the stream-power model needs 3 x 3 vertices or more (the edges are base level)");
  const double q = state_.terrain().quantum();
  std::vector<float> rate(static_cast<std::size_t>(nx) * ny, static_cast<float>(settings_.uplift));
  if (!settings_.uplift_file.empty()) {
    rate = read_vertex_raster(
        settings_.uplift_file, nx, ny, "stream_power.uplift_file",
        [](float u) { return u >= 0 ? "" : "an uplift rate must be finite and ≥ 0 mm/yr"; });
  }
  uplift_per_step_.assign(rate.size(), 0);
  uplift_rate_.assign(rate.size(), 0.0f);
  next_dt_ = settings_.dt;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      if (!is_base_level(i, j, nx, ny, base_)) {
        const std::size_t k = static_cast<std::size_t>(j) * nx + i;
        uplift_rate_[k] = rate[k];
        uplift_per_step_[k] = std::llround(rate[k] * 1e-3 * settings_.dt / q);
      }
  k_.assign(rate.size(), settings_.k);
}

double StreamPowerModel::take_step() {
  DeviceTerrain& terrain = state_.terrain();
  const int nx = terrain.nx(), ny = terrain.ny();
  const double q = terrain.quantum();
  terrain.download_fixed(fixed_);
  const double dt = next_dt_;
  next_dt_ = settings_.dt;
  // A whole step's uplift, or a shortened step's own (kept apart for uplift_per_vertex()).
  std::vector<std::int64_t> shortened;
  if (dt != settings_.dt) {
    shortened.resize(uplift_rate_.size());
    for (std::size_t k = 0; k < shortened.size(); ++k)
      shortened[k] = std::llround(uplift_rate_[k] * 1e-3 * dt / q);
    if (uplift_partial_.empty()) uplift_partial_.assign(shortened.size(), 0);
    for (std::size_t k = 0; k < shortened.size(); ++k) uplift_partial_[k] += shortened[k];
    ++partial_steps_;
  }
  const std::vector<std::int64_t>& uplift = shortened.empty() ? uplift_per_step_ : shortened;
  std::vector<double>& h = height_;
  h.resize(fixed_.size());
  for (std::size_t k = 0; k < fixed_.size(); ++k) {
    fixed_[k] += uplift[k];
    uplift_ += uplift[k];
    h[k] = static_cast<double>(fixed_[k]) * q;
  }
  if (ground_) {  // the strata rise with the rock; K × the exposed rock's erodibility
    ground_->raise(uplift);
    const std::vector<float> e = ground_->rock_erodibility();
    for (std::size_t k = 0; k < k_.size(); ++k) k_[k] = settings_.k * e[k];
  }
  const FlowRouting& routing = router_.route(h);
  if (settings_.deposition > 0) before_ = h;
  erode_stream_power(h, routing, k_, settings_.m, settings_.n, dt);
  if (settings_.deposition > 0)
    deposit_sediment_flux(h, before_, routing, settings_.deposition,
                          terrain.cell() * terrain.cell());
  diffuse(h, nx, ny, terrain.cell(), settings_.diffusivity, dt, base_);
  // Back to whole quanta; what the interior lost left the map over the base level.
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (is_base_level(i, j, nx, ny, base_)) continue;
      const std::size_t k = static_cast<std::size_t>(j) * nx + i;
      const std::int64_t now = std::llround(h[k] / q);
      outflow_ += fixed_[k] - now;
      fixed_[k] = now;
    }
  terrain.upload_fixed(fixed_);
  return dt;
}

std::vector<std::int64_t> StreamPowerModel::uplift_per_vertex() {
  // The rate is the same every step, so the uplift so far is the rate times the whole steps (a
  // resumed run included), and what the shortened ones added.
  std::vector<std::int64_t> total(uplift_per_step_);
  const auto whole = static_cast<std::int64_t>(steps()) - partial_steps_;
  for (std::size_t k = 0; k < total.size(); ++k)
    total[k] = total[k] * whole + (uplift_partial_.empty() ? 0 : uplift_partial_[k]);
  return total;
}

std::vector<std::pair<std::string, std::int64_t>> StreamPowerModel::counters() {
  std::vector<std::pair<std::string, std::int64_t>> c = {{"outflow_quanta", outflow_},
                                                         {"uplift_quanta", uplift_}};
  if (partial_steps_ > 0) c.emplace_back("partial_steps", partial_steps_);
  return c;
}

void StreamPowerModel::store_own_fields(std::vector<StoredField>& fields) {
  if (!uplift_partial_.empty()) fields.push_back({kPartialUplift, 1, {}, uplift_partial_});
}

void StreamPowerModel::restore_own_fields(const std::vector<StoredField>& fields) {
  uplift_partial_.clear();
  for (const StoredField& f : fields)
    if (f.name == kPartialUplift) uplift_partial_ = f.i64;
}

void StreamPowerModel::restore_counters(
    const std::vector<std::pair<std::string, std::int64_t>>& c) {
  outflow_ = counter_value(c, "outflow_quanta");
  uplift_ = counter_value(c, "uplift_quanta");
  partial_steps_ = 0;
  for (const auto& [name, value] : c)
    if (name == "partial_steps") partial_steps_ = value;
}

JsonObject StreamPowerModel::diagnostics() {
  // The slope–area relation of the channels now (nodes draining 10 cells or more): S = k_s A^−θ.
  DeviceTerrain& terrain = state_.terrain();
  const std::vector<std::int64_t> fixed = terrain.download_fixed();
  std::vector<double> h(fixed.size());
  for (std::size_t k = 0; k < h.size(); ++k)
    h[k] = static_cast<double>(fixed[k]) * terrain.quantum();
  const FlowRouting& r = router_.route(h);
  const SlopeArea fit = fit_slope_area(h, r, 10.0 * terrain.cell() * terrain.cell());
  return JsonObject()
      .add("uplift_volume_m3", static_cast<double>(uplift_) * terrain.volume_quantum())
      .add("years", time())
      .add("concavity_theta", fit.theta)
      .add("steepness_ks", fit.ks)
      .add("channel_nodes", fit.nodes);
}

}  // namespace runnel
