// SPDX-License-Identifier: MIT
// Stepped heights (height_steps.hpp): a staircase of whole steps is told from smooth terrain and
// from a plain with a hill on it, with shares counted by hand; the shipped DEM is stepped, and a
// run on it says so before it starts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/height_steps.hpp"
#include "runnel/terrain/terrain_io.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

TEST(HeightSteps, AStaircaseIsSteppedWithTheSharesItsTreadsAndRisersGive) {
  // Treads three vertices wide, risers of 0.5 m, along x; level along z. Of the x-pairs, one in
  // three is a riser: 40 columns give 39 pairs a row, 13 of them risers; every z-pair is level.
  Heightmap t(40, 20, 1.0);
  for (int j = 0; j < t.ny; ++j)
    for (int i = 0; i < t.nx; ++i) t.at(i, j) = 0.5f * static_cast<float>(i / 3);
  const HeightSteps s = height_steps(t);
  const double pairs = 39.0 * 20 + 40.0 * 19;
  EXPECT_FLOAT_EQ(s.step, 0.5);
  EXPECT_NEAR(s.one_step_share, 13.0 * 20 / pairs, 1e-12);
  EXPECT_NEAR(s.level_share, (26.0 * 20 + 40.0 * 19) / pairs, 1e-12);
  // Risers are 0.34 of the level pairs here: under the DEM's 1.2–1.9, so not a staircase yet by the
  // rule; with risers every other vertex it is.
  EXPECT_FALSE(s.stepped());
  for (int j = 0; j < t.ny; ++j)
    for (int i = 0; i < t.nx; ++i) t.at(i, j) = 0.5f * static_cast<float>(i / 2 + j / 2);
  EXPECT_TRUE(height_steps(t).stepped()) << height_steps(t).caution();
  EXPECT_NE(height_steps(t).caution().find("steps of 0.5 m"), std::string::npos);
}

TEST(HeightSteps, GeneratedHillsAndAHillOnAPlainAreNotStepped) {
  const Heightmap hills = generate_terrain("fbm", 65, 65, 2.0, 7, {{"relief", 0.12}});
  const HeightSteps h = height_steps(hills);
  EXPECT_LT(h.level_share, 0.001);
  EXPECT_FALSE(h.stepped());
  EXPECT_TRUE(h.caution().empty());
  // A pyramid of constant slope on a flat plain: most pairs level, its faces one "step" apart, but
  // few of them against the plain's level pairs.
  Heightmap plain(64, 64, 1.0);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i)
      plain.at(i, j) =
          0.3f * static_cast<float>(std::max(0, 8 - std::max(std::abs(i - 32), std::abs(j - 32))));
  const HeightSteps p = height_steps(plain);
  EXPECT_GT(p.level_share, 0.8);
  EXPECT_FALSE(p.stepped());
  // A flat terrain has no step at all.
  EXPECT_FALSE(height_steps(Heightmap(16, 16, 1.0, 3.0f)).stepped());
}

TEST(HeightSteps, APlaneOfConstantSlopeIsNotSteppedThoughItsHeightsComeInEqualSteps) {
  // A 5 % plane along x on 0.5 m cells, the plane generator's and at an angle: its pairs along x
  // are all one step (2.5 cm) apart and across it all level, half and half, as a staircase's could
  // be; but no tread ends on a riser.
  const auto plane = [](int nx, int ny, double cell, double azimuth_deg) {
    Heightmap t(nx, ny, cell);
    const double a = azimuth_deg * M_PI / 180;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        t.at(i, j) = static_cast<float>(0.05 * cell * (std::cos(a) * i + std::sin(a) * j));
    return t;
  };
  const HeightSteps along = height_steps(plane(200, 40, 0.5, 0));
  EXPECT_NEAR(along.level_share, 0.5, 0.01);
  EXPECT_NEAR(along.one_step_share, 0.5, 0.01);
  EXPECT_EQ(along.tread_end_share, 0.0);
  EXPECT_FALSE(along.stepped()) << along.caution();
  EXPECT_FALSE(height_steps(plane(65, 65, 1.0, 30)).stepped());
  const Heightmap generated =
      generate_terrain("plane", 129, 33, 0.5, 1, {{"slope", 5.0}, {"azimuth", 90.0}});
  EXPECT_FALSE(height_steps(generated).stepped()) << height_steps(generated).caution();
  // The same heights cut into treads two cells wide both ways are a staircase.
  Heightmap stairs(200, 40, 0.5);
  for (int j = 0; j < stairs.ny; ++j)
    for (int i = 0; i < stairs.nx; ++i)
      stairs.at(i, j) = 0.025f * static_cast<float>(i / 2 + j / 2);
  const HeightSteps s = height_steps(stairs);
  EXPECT_GT(s.tread_end_share, 0.2);
  EXPECT_TRUE(s.stepped());
}

TEST(HeightSteps, TheShippedDemIsSteppedAndARunOnItSaysSoFirst) {
  const std::string dem = test::source_dir() + "/data/terrains/jacksboro_fault_dem.asc";
  const HeightSteps s = height_steps(read_terrain(dem));
  EXPECT_FLOAT_EQ(s.step, 1.0);  // stored in whole metres
  EXPECT_TRUE(s.stepped());
  test::ScratchDir dir;
  const auto r = test::run_cli({"run", "--terrain", dem, "--steps", "2", "--out", dir.path("dem")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto caution = r.err.find("caution: the terrain's heights come in steps of 1 m");
  EXPECT_NE(caution, std::string::npos) << r.err;
  EXPECT_LT(caution, r.err.find("mass balance")) << "the caution comes before the run:\n" << r.err;
  EXPECT_NE(test::read_text(dir.path("dem/metrics.json")).find("\"stepped\": true"),
            std::string::npos);
}

TEST(HeightSteps, ACompareReportListsTheTerrainsStepsAmongItsCautions) {
  test::ScratchDir dir;
  const auto r = test::run_cli({"compare", "--models", "thermal", "--terrain",
                                test::source_dir() + "/data/terrains/jacksboro_se_scaled.asc",
                                "--set", "run.iterations=1", "--out", dir.path("cmp")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string report = test::read_text(dir.path("cmp/report.md"));
  EXPECT_NE(report.find("Cautions:\n\n- terrain: the terrain's heights come in steps of 0.024 m"),
            std::string::npos)
      << report;
}

}  // namespace
}  // namespace runnel
