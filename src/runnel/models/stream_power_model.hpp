// SPDX-License-Identifier: MIT
#pragma once
#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "runnel/landscape/flow_routing.hpp"
#include "runnel/models/grid_model.hpp"

namespace runnel {

struct StreamPowerSettings {
  // The stream_power.* parameters (defaults, units, meaning: the table in stream_power_model.cpp).
  double k;                 // erodibility K, m^(1−2m)/yr
  double m, n;              // area and slope exponents
  double uplift;            // U, mm/yr
  std::string uplift_file;  // raster of U, mm/yr
  double diffusivity;       // D, m²/yr
  double dt;                // yr per step
  std::string base_level;   // "all" edges, or "west-east"
  double deposition;        // G of the erosion-deposition (xi-q) form; 0: detachment-limited
  static StreamPowerSettings from(const Parameters& params);
};

// Erosion_BraunWillett2013: detachment-limited stream-power incision E = K A^m S^n over years, with
// tectonic uplift and linear hillslope diffusion (docs/models.md "stream-power"). One step of dt:
// uplift the interior, route D8 over the depression-filled surface (basin graph), the implicit
// O(n) stream-power update in stack order (Braun & Willett 2013), diffusion; the edges are base
// level. On the host: the stack order is sequential. Heights stay integer quanta: what a step
// removes leaves the map (outflow) and the uplift is booked, so the balance is exact.
class StreamPowerModel final : public GridModel {
 public:
  static const ModelInfo& model_info();
  StreamPowerModel(ComputeContext& compute, const Parameters& params, const Heightmap& terrain);
  const ModelInfo& info() const override { return model_info(); }

  long long outflow_quanta() override { return outflow_; }
  long long uplift_quanta() override { return uplift_; }
  std::vector<std::int64_t> uplift_per_vertex() override;
  JsonObject diagnostics() override;
  double next_dt() const override { return next_dt_; }
  // advance() and BMI's update_until land on their target: the last step is shortened to it,
  // its uplift the rate times its own length (kept per vertex, so the balance stays exact).
  void limit_next_step(double most) override { next_dt_ = std::min(settings_.dt, most); }

 protected:
  double take_step() override;
  std::vector<std::pair<std::string, std::int64_t>> counters() override;
  void restore_counters(const std::vector<std::pair<std::string, std::int64_t>>& c) override;
  void restore_next_dt(double dt) override { next_dt_ = dt; }
  void store_own_fields(std::vector<StoredField>& fields) override;
  void restore_own_fields(const std::vector<StoredField>& fields) override;

 private:
  StreamPowerSettings settings_;
  std::vector<std::int64_t> uplift_per_step_;  // quanta per vertex and step (0 on the edges)
  std::vector<float> uplift_rate_;             // mm/yr per vertex (0 on the edges)
  double next_dt_ = 0;                         // yr: settings_.dt, or less to land on a target
  // The uplift of the shortened steps, quanta per vertex (empty: none), and how many there were.
  std::vector<std::int64_t> uplift_partial_;
  long long partial_steps_ = 0;
  std::vector<double> k_;  // K per vertex
  BaseLevel base_;
  D8Router router_;
  // Per-step working memory, kept: fresh pages for them every step were a tenth of its time.
  std::vector<std::int64_t> fixed_;
  std::vector<double> height_, before_;
  long long outflow_ = 0, uplift_ = 0;
};

}  // namespace runnel
