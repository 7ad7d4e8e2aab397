// SPDX-License-Identifier: MIT
// The dam break's score: the simulated surge distance against a reading of an experiment's
// (validation.hpp, score_surge_front).
#include <algorithm>
#include <cmath>

#include "runnel/validation/validation.hpp"

namespace runnel {

SurgeScore score_surge_front(const std::vector<std::pair<double, double>>& front,
                             const std::vector<FrontSample>& measured, double tank_length) {
  SurgeScore score;
  if (front.size() < 2) return score;
  for (const FrontSample& m : measured) {
    const double surge_measured = m.x_over_l - 1.0;
    if (surge_measured <= 0.0 || m.x_over_l >= tank_length) continue;
    if (m.t_star < front.front().first || m.t_star > front.back().first) continue;
    const auto after =
        std::lower_bound(front.begin(), front.end(), m.t_star,
                         [](const auto& sample, double t) { return sample.first < t; });
    const auto before = after == front.begin() ? after : after - 1;
    const double span = after->first - before->first;
    const double x = span > 0 ? before->second + (after->second - before->second) *
                                                     (m.t_star - before->first) / span
                              : after->second;
    const double error = std::fabs((x - 1.0) - surge_measured) / surge_measured;
    score.points.push_back({m.t_star, m.x_over_l, x, error});
    score.mean += error;
    score.worst = std::max(score.worst, error);
  }
  if (!score.points.empty()) score.mean /= static_cast<double>(score.points.size());
  return score;
}

}  // namespace runnel
