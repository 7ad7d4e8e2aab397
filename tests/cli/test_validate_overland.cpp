// SPDX-License-Identifier: MIT
// `runnel validate overland`: a small plane (20 m, 0.1 m cells, k = 12) with the default flux
// against the kinematic wave, the outputs a run leaves, and the planes and spacings it refuses.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "runnel/core/text.hpp"
#include "runnel/validation/kinematic_wave.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

// Every number after `"key": ` in `json`, in order.
std::vector<double> all_numbers(const std::string& json, const std::string& key) {
  std::vector<double> v;
  const std::string tag = "\"" + key + "\": ";
  for (std::size_t at = json.find(tag); at != std::string::npos; at = json.find(tag, at + 1))
    v.push_back(std::stod(json.substr(at + tag.size())));
  return v;
}

TEST(ValidateOverlandCli, TheDefaultFluxRunsOffASmallPlaneAsTheKinematicWaveSays) {
  test::ScratchDir dir;
  const auto r = test::run_cli({"validate", "overland", "--models", "godunov", "--length", "20",
                                "--rain", "80000", "--out", dir.path("out")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The case as posed: the analytic figures come from the parameters alone.
  KinematicPlane plane;
  plane.length = 20, plane.slope = 0.2, plane.manning_n = 0.1, plane.rain = 80000 / 3.6e6;
  EXPECT_NEAR(test::json_number(r.out, "equilibrium_time_s"), plane.equilibrium_time(), 1e-9);
  EXPECT_GE(test::json_number(r.out, "kinematic_number"), 10);
  // Water is conserved to the float depths' round-off, and all the rain leaves at equilibrium:
  // nothing piles up at the open foot.
  EXPECT_LT(std::fabs(test::json_number(r.out, "water_balance_rel")), 1e-4);
  EXPECT_LT(std::fabs(test::json_number(r.out, "equilibrium_outflow_error")), 0.01);
  // The depths along the plane, the hydrograph and the water stored, against the analytic values
  // (the targets are 10 %, 5 % and 5 %; at this cell 5.6 %, 5.5 % and 3.2 %). Where the faces saw
  // the bed as steps, the first gauge's sheet (S l / 2h = 9 % of a step) was 10 % too deep.
  const std::vector<double> errors = all_numbers(r.out, "error");
  ASSERT_EQ(errors.size(), 9u) << r.out;
  for (double e : errors) EXPECT_LT(std::fabs(e), 0.07) << r.out;
  EXPECT_LT(errors.back(), 0.04) << "the last gauge, 2 m above the foot";
  EXPECT_LT(test::json_number(r.out, "outflow_worst_error_of_iA"), 0.065);
  EXPECT_LT(std::fabs(test::json_number(r.out, "storage_error")), 0.045);
  EXPECT_NE(test::read_text(dir.path("out/overland.json")).find("\"equilibrium_time_s\""),
            std::string::npos);
  EXPECT_NE(test::read_text(dir.path("out/godunov/outflow.csv")).find("t,rain,outflow,stored"),
            std::string::npos);
}

TEST(ValidateOverlandCli, BothSphSolversCarryTheRainOffAShortPlane) {
  // 10 m under 200 mm/h·1000 (k = 5.2, t_e = 5.1 s), 0.1 m particles: too shallow for a gauge
  // three particles deep, but the water's budget and the hydrograph are scored. The walls stay
  // put (nothing erodes or slumps), so what is stored is the sheet's own water.
  test::ScratchDir dir;
  const auto r = test::run_cli({"validate", "overland", "--models", "wcsph,dfsph", "--length", "10",
                                "--rain", "200000", "--spacing", "0.1", "--out", dir.path("out")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<double> balance = all_numbers(r.out, "water_balance_rel");
  const std::vector<double> equilibrium = all_numbers(r.out, "equilibrium_outflow_error");
  const std::vector<double> storage = all_numbers(r.out, "storage_error");
  const std::vector<double> rise = all_numbers(r.out, "rise_time_95_error");
  const std::vector<double> bed = all_numbers(r.out, "bed_moved_m3");
  ASSERT_EQ(balance.size(), 2u) << r.out;
  for (int k = 0; k < 2; ++k) {
    EXPECT_LT(bed[k], 1e-4) << "the walls slumped or the bed eroded (float round-off: 10⁻⁷ m³)";
    EXPECT_LT(std::fabs(balance[k]), 1e-12) << "particles are counted, not summed";
    EXPECT_LT(std::fabs(equilibrium[k]), 0.05) << r.out;
    EXPECT_LT(std::fabs(storage[k]), 0.35) << r.out;
    EXPECT_LT(std::fabs(rise[k]), 0.15) << r.out;
  }
  EXPECT_TRUE(std::filesystem::exists(dir.path("out/dfsph-0.1/outflow.csv")));
}

// dfsph with the terrain as mirror images and the rain entering at the water's surface, on the same
// short plane for twice its t_e: the walls' feet (where a face passes nearer than the contact
// keeps a particle) and the drops over the sheet carry it to the end with the water's budget closed
// and the equilibrium outflow at the rain's.
TEST(ValidateOverlandCli, DfsphWithFloorImagesCarriesTheRainOffAShortPlane) {
  test::ScratchDir dir;
  const auto r =
      test::run_cli({"validate", "overland", "--models", "dfsph", "--length", "10", "--rain",
                     "200000", "--spacing", "0.1", "--set", "sph.dfsph_floor_images=true", "--set",
                     "rain.above_water=true", "--out", dir.path("out")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(r.out.find("\"error\": \""), std::string::npos) << r.out;  // no run stopped
  EXPECT_LT(std::fabs(test::json_number(r.out, "water_balance_rel")), 1e-12);
  EXPECT_LT(std::fabs(test::json_number(r.out, "equilibrium_outflow_error")), 0.05) << r.out;
  EXPECT_LT(std::fabs(test::json_number(r.out, "rise_time_95_error")), 0.15) << r.out;
}

// The flow's Froude number each pipe run reports (weighted by discharge) against the kinematic
// sheet's, F(x) = (√S/n) h(x)^(2/3) / √(g h(x)) ∝ x^(1/10) weighted by q = i x: (20/21) F(L). On
// the steep plane (F(L) = 1.13) the local-inertial flux's equations turn the sheet into roll waves
// (they hold it only below 3/5) and its run says so; on a plane ten times gentler (F(L) = 0.36,
// the same depths) it does not.
TEST(ValidateOverlandCli, TheLocalInertialFluxSaysWhenTheFlowIsTooFastForItsEquations) {
  for (const double slope : {0.2, 0.02}) {
    KinematicPlane plane;
    plane.length = 20, plane.slope = slope, plane.manning_n = 0.1;
    plane.rain = 80000 / 3.6e6 * std::sqrt(slope / 0.2);  // the same depths on either plane
    const double foot = plane.equilibrium_depth(plane.length);
    const double sheet_froude =
        20.0 / 21.0 * plane.alpha() * std::pow(foot, 2.0 / 3.0) / std::sqrt(9.81 * foot);
    const auto r = test::run_cli(
        {"validate", "overland", "--models", "godunov,local-inertial", "--cell", "0.2", "--length",
         "20", "--slope", format_number(slope), "--rain", format_number(plane.rain * 3.6e6)});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::vector<double> froude = all_numbers(r.out, "flow_froude_max");
    ASSERT_EQ(froude.size(), 2u) << r.out;
    EXPECT_NEAR(froude[0], sheet_froude, 0.06 * sheet_froude) << "godunov, slope " << slope;
    // One caution at most, the local-inertial run's: godunov carries the sheet at either slope.
    const std::size_t caution = r.out.find("\"caution\": ");
    EXPECT_EQ(caution != std::string::npos, slope > 0.1) << r.out;
    if (caution != std::string::npos) {
      EXPECT_NE(r.out.find("local-inertial\\\": the flow reached Froude", caution),
                std::string::npos);
      EXPECT_EQ(r.out.find("\"caution\": ", caution + 1), std::string::npos) << r.out;
    }
  }
}

TEST(ValidateOverlandCli, ARunThatStopsIsReportedAndTheOthersGoOn) {
  // A density limit every SPH run crosses at once: each stops as unstable, godunov still runs.
  const auto r =
      test::run_cli({"validate", "overland", "--models", "wcsph,godunov", "--length", "20",
                     "--rain", "80000", "--spacing", "0.1", "--set", "sph.density_max=1.001"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("wcsph at 0.1 m stopped: SPH step"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("\"error\": \"SPH step"), std::string::npos) << r.out;
  EXPECT_EQ(all_numbers(r.out, "depth_gauges_scored").size(), 1u) << "godunov's scores";
  EXPECT_NE(r.out.find("\"all_targets_met\": false"), std::string::npos);
}

TEST(ValidateOverlandCli, RefusesAPlaneOutsideTheKinematicWaveAndTooCoarseASpacing) {
  test::ScratchDir dir;
  // 5 m of smooth plane: k = L g n² / h_L^(4/3) far below 3.
  const auto short_plane = test::run_cli(
      {"validate", "overland", "--length", "5", "--manning-n", "0.02", "--out", dir.path("a")});
  EXPECT_EQ(short_plane.exit_code, 2);
  EXPECT_NE(short_plane.err.find("kinematic number k"), std::string::npos) << short_plane.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("a")));
  // 0.5 m particles in a sheet 0.55 m deep at the foot: fewer than two.
  const auto coarse = test::run_cli(
      {"validate", "overland", "--models", "wcsph", "--spacing", "0.5", "--out", dir.path("b")});
  EXPECT_EQ(coarse.exit_code, 2);
  EXPECT_NE(coarse.err.find("at most 0.27"), std::string::npos) << coarse.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("b")));
  const auto other_case = test::run_cli({"validate", "dambreak", "--slope", "0.1"});
  EXPECT_EQ(other_case.exit_code, 2);
  EXPECT_NE(other_case.err.find("--slope"), std::string::npos) << other_case.err;
  const auto unknown = test::run_cli({"validate", "overland", "--models", "pipe"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("unknown run 'pipe'"), std::string::npos) << unknown.err;
}

}  // namespace
}  // namespace runnel
