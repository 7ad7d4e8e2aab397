// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "runnel/models/model.hpp"

namespace runnel {

// outflow.csv: the water's budget every run.outflow_every of the model's clock, the discharge
// hydrograph a hydrologist reads first (docs/guide.md, "The hydrograph"). Each row, at the first
// step that reaches a sampling time k · every, holds
//   t, rain, outflow (the mean rates since the row before, volume per clock unit),
//   stored (the water on the terrain now), rain_volume, outflow_volume (the running totals),
// and with per_edge the outflow rate over each edge. The recorder's place (the next sampling time
// and the last row's totals) travels in the checkpoints, so a resumed run writes the rows the
// uninterrupted run writes from there on, bit for bit.
// One row of the hydrograph: the time and the mean outflow rate since the row before.
struct HydrographPoint {
  double t = 0, outflow = 0;
};

class Hydrograph {
 public:
  // `every` 0 records nothing. `start` is the budget where the run begins.
  Hydrograph(double every, bool per_edge, double t0, const WaterBudget& start);
  bool active() const { return every_ > 0; }
  bool due(double t) const { return active() && t >= (next_ - 1e-9) * every_; }
  void record(double t, const WaterBudget& budget);
  std::string csv() const;
  std::size_t rows() const { return points_.size(); }
  // The rows this recorder wrote (t, outflow), as outflow.csv holds them.
  const std::vector<HydrographPoint>& points() const { return points_; }

  // The recorder's place as named checkpoint counters, and back from a checkpoint's counters (a
  // file without them: the recorder starts where the run resumes).
  std::vector<std::pair<std::string, std::int64_t>> place() const;
  void resume_from(const std::vector<std::pair<std::string, std::int64_t>>& counters);

 private:
  double every_;
  bool per_edge_;
  long long next_ = 1;  // the next row is at next_ · every_
  double last_t_;
  WaterBudget last_;
  std::string text_;
  std::vector<HydrographPoint> points_;
};

}  // namespace runnel
