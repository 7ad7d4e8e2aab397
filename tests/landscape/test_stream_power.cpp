// SPDX-License-Identifier: MIT
// The stream-power model against its analytic steady states (docs/models.md "stream-power"):
// fastscapelib's 1-D bedrock channel for n = 1, 2, 4 to 1e-5, a 2-D grid's slope–area relation at
// every channel node to 1e-3 with the fitted concavity m/n, the diffusion hillslope S = U x / D;
// the D8 routing against a brute-force steepest descent; the model's exact balance with uplift.
#include <gtest/gtest.h>

#include <cmath>

#include "runnel/landscape/flow_routing.hpp"
#include "runnel/landscape/stream_power.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/validation/stream_power_validation.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

TEST(StreamPower, TheOneDimensionalChannelReachesTheAnalyticSteadyState) {
  for (double n : {1.0, 2.0, 4.0}) {
    const SteadyStateCheck c = stream_power_profile(n);
    EXPECT_EQ(c.nodes, 100);
    EXPECT_LT(c.worst_relative, 1e-5) << "n = " << n;
    EXPECT_NEAR(c.fitted_theta, 0.5 / n, 1e-5) << "n = " << n;
  }
}

TEST(StreamPower, EveryChannelNodeOfAGridFollowsTheSlopeAreaRelation) {
  for (double n : {1.0, 2.0}) {
    const SteadyStateCheck c = stream_power_grid(41, n, 4);
    EXPECT_GT(c.nodes, 100);
    EXPECT_LT(c.worst_relative, 1e-3) << "n = " << n;
    EXPECT_NEAR(c.fitted_theta, 0.5 / n, 1e-3) << "n = " << n;
  }
}

TEST(StreamPower, DiffusionAloneReachesTheParabolicHillslope) {
  const SteadyStateCheck c = hillslope_diffusion();
  EXPECT_EQ(c.nodes, 100);
  EXPECT_LT(c.worst_relative, 1e-3);
}

TEST(StreamPower, D8SendsEveryNodeDownItsSteepestDescentAndTheStackPutsReceiversFirst) {
  // A cone has no depression: on it the filled surface is the surface itself.
  const Heightmap t = generate_terrain("cone", 40, 30, 5.0, 3, {{"radius", 0.9}});
  std::vector<double> h(t.h.begin(), t.h.end());
  const FlowRouting r = route_d8(h, t.nx, t.ny, t.cell);
  std::vector<int> position(h.size(), -1);
  for (std::size_t s = 0; s < r.stack.size(); ++s) position[r.stack[s]] = static_cast<int>(s);
  double total_area = 0;
  for (int j = 0; j < t.ny; ++j)
    for (int i = 0; i < t.nx; ++i) {
      const int k = j * t.nx + i;
      ASSERT_GE(position[k], 0) << "every node is on the stack";
      EXPECT_LT(position[r.receiver[k]], position[k] + (r.receiver[k] == k ? 1 : 0));
      if (r.receiver[k] == k) {
        total_area += r.area[k];
        continue;
      }
      // Brute force: no neighbour is lower (on the filled surface the receiver is the steepest;
      // on the raw one, outside depressions, the same).
      double steepest = 0;
      for (int b = j - 1; b <= j + 1; ++b)
        for (int a = i - 1; a <= i + 1; ++a) {
          if (a == i && b == j) continue;
          const double s =
              (h[k] - h[b * t.nx + a]) / std::hypot((a - i) * t.cell, (b - j) * t.cell);
          steepest = std::max(steepest, s);
        }
      if (steepest > 0) {
        EXPECT_NEAR((h[k] - h[r.receiver[k]]) / r.distance[k], steepest, 1e-9) << i << "," << j;
      }
    }
  EXPECT_NEAR(total_area, double(t.nx) * t.ny * t.cell * t.cell, 1e-6)
      << "all area reaches base level";
}

TEST(StreamPower, TheModelBooksUpliftAndOutflowExactly) {
  Parameters p = default_parameters();
  p.set("run.model", std::string("stream-power"));
  p.set("stream_power.k", 1e-4);
  p.set("stream_power.diffusivity", 0.05);
  auto model =
      make_model(test::compute(), p, generate_terrain("fbm", 33, 33, 20.0, 2, {{"relief", 0.1}}));
  for (int s = 0; s < 20; ++s) model->step();
  const MassBalance m = model->mass_balance();
  EXPECT_GT(m.uplift, 0.0);
  EXPECT_GT(m.outflow, 0.0);
  EXPECT_EQ(m.residual_quanta, 0);
  EXPECT_DOUBLE_EQ(model->time(), 20 * 1000.0);
}

TEST(StreamPower, AShortenedStepLandsOnItsTargetWithItsOwnUplift) {
  // update_until(2,500 yr) with steps of 1,000 yr: two whole steps and one of 500 yr, whose uplift
  // is the rate times 500 yr; the interior rose by U t in all, the balance exact.
  Parameters p = default_parameters();
  p.set("run.model", std::string("stream-power"));
  p.set("stream_power.k", 1e-4);
  auto model =
      make_model(test::compute(), p, generate_terrain("fbm", 33, 33, 20.0, 2, {{"relief", 0.1}}));
  model->advance(2500.0);
  EXPECT_DOUBLE_EQ(model->time(), 2500.0);
  EXPECT_EQ(model->steps(), 3u);
  EXPECT_DOUBLE_EQ(model->step_size(), 1000.0) << "the next step is a whole one again";
  const MassBalance m = model->mass_balance();
  EXPECT_EQ(m.residual_quanta, 0);
  const double interior = 31.0 * 31.0 * 20.0 * 20.0;  // m², the edges are base level
  EXPECT_NEAR(m.uplift, interior * 1e-3 * 2500.0, 1e-9 * m.uplift) << "U = 1 mm/yr over 2,500 yr";
  const std::vector<double> risen = [&] {
    std::vector<double> r;
    const Heightmap reference = model->erosion_reference(), initial = model->initial_terrain();
    for (std::size_t k = 0; k < initial.h.size(); ++k) r.push_back(reference.h[k] - initial.h[k]);
    return r;
  }();
  EXPECT_NEAR(risen[16 * 33 + 16], 2.5, 1e-4) << "the erosion maps' surface rose by U t";
  EXPECT_EQ(risen[0], 0.0) << "not the base level";
}

TEST(StreamPower, ErosionIsMeasuredFromTheUpliftedSurface) {
  // Detachment-limited incision without diffusion only ever lowers a vertex below where the uplift
  // put it, and all it removes leaves the map: measured from the uplifted surface, nothing is
  // deposited and the eroded volume is the outflow. The erosion map is that difference.
  Parameters p = default_parameters();
  p.set("run.model", std::string("stream-power"));
  p.set("stream_power.k", 1e-4);
  const Heightmap t = generate_terrain("fbm", 33, 33, 20.0, 2, {{"relief", 0.1}});
  auto model = make_model(test::compute(), p, t);
  for (int s = 0; s < 20; ++s) model->step();
  const MassBalance m = model->mass_balance();
  EXPECT_GT(m.eroded, 0.0);
  EXPECT_EQ(m.deposited, 0.0);
  EXPECT_NEAR(m.eroded, m.outflow, 1e-9 * m.outflow);
  const Heightmap reference = model->erosion_reference(), now = model->terrain();
  const double rise = 20 * 1000.0 * 1e-3;  // 20 steps of 1000 yr at 1 mm/yr
  EXPECT_NEAR(reference.at(16, 16) - t.at(16, 16), rise, 1e-3) << "an interior vertex rose";
  EXPECT_EQ(reference.at(0, 16), t.at(0, 16)) << "the base level did not";
  for (std::size_t k = 0; k < now.h.size(); ++k)
    EXPECT_LE(now.h[k], reference.h[k] + 1e-3) << "vertex " << k << " above the uplifted surface";
}

TEST(StreamPower, TheErosionDepositionFormDepositsWhereTheDetachmentLimitedOneCannot) {
  // Without uplift nothing can rise in the detachment-limited form; with G > 0 the flux from
  // upstream settles in the valleys and lows rise. Both balance exactly.
  for (double g : {0.0, 1.0}) {
    Parameters p = default_parameters();
    p.set("run.model", std::string("stream-power"));
    p.set("stream_power.uplift", 0.0);
    p.set("stream_power.k", 1e-4);
    p.set("stream_power.deposition", g);
    auto model =
        make_model(test::compute(), p, generate_terrain("fbm", 33, 33, 20.0, 2, {{"relief", 0.1}}));
    for (int s = 0; s < 10; ++s) model->step();
    const MassBalance m = model->mass_balance();
    EXPECT_EQ(m.residual_quanta, 0) << "G " << g;
    EXPECT_GT(m.eroded, 0.0);
    if (g == 0) {
      EXPECT_EQ(m.deposited, 0.0);
    } else {
      EXPECT_GT(m.deposited, 0.0);
    }
  }
}

TEST(StreamPower, ItsMetricsReportTheConcavityOfItsChannels) {
  // Run towards steady state under uplift: the fitted θ of the channels approaches m/n = 0.5.
  Parameters p = default_parameters();
  p.set("run.model", std::string("stream-power"));
  p.set("stream_power.k", 2e-5);
  p.set("stream_power.dt", 20000.0);
  auto model =
      make_model(test::compute(), p, generate_terrain("fbm", 33, 33, 100.0, 4, {{"relief", 0.01}}));
  for (int s = 0; s < 300; ++s) model->step();
  const std::string d = model->diagnostics().str();
  EXPECT_NEAR(test::json_number(d, "concavity_theta"), 0.5, 0.02) << d;
  EXPECT_GT(test::json_number(d, "steepness_ks"), 0.0);
}

}  // namespace
}  // namespace runnel
