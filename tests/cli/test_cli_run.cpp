// SPDX-License-Identifier: MIT
// `runnel run` end to end: outputs, metrics.json keys, bad scenario values, a real DEM.
#include <gtest/gtest.h>

#include <filesystem>

#include "runnel/terrain/terrain_io.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::run_cli;
using test::ScratchDir;

TEST(CliRun, WritesPicturesTerrainAndMetrics) {
  ScratchDir dir;
  const auto r =
      run_cli({"run", "--generate", "fbm", "--set", "terrain.size=65", "--set", "terrain.cell=1",
               "--steps", "150", "--seed", "3", "--out", dir.path("out"), "--set", "rain.rate=2000",
               "--trace", dir.path("trace.json")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"height_initial.png", "height_final.png", "erosion.png", "final.asc",
                        "final.npy", "metrics.json"}) {
    EXPECT_TRUE(std::filesystem::exists(dir.path(std::string("out/") + f))) << f;
  }
  const std::string metrics = test::read_text(dir.path("out/metrics.json"));
  for (const char* key : {"steps",
                          "sim_time",
                          "wall_seconds",
                          "particle_steps_per_second",
                          "particles_spawned",
                          "particles_alive",
                          "eroded_volume",
                          "deposited_volume",
                          "outflow_volume",
                          "suspended_volume",
                          "mass_balance_abs",
                          "mass_balance_rel",
                          "below_surface_projections",
                          "collisions",
                          "seed",
                          "model",
                          "parameters",
                          "effective",
                          "kernel_seconds",
                          "kernel_launches",
                          "kernel_waits",
                          "device_idle_seconds"}) {
    EXPECT_NE(metrics.find(std::string("\"") + key + "\""), std::string::npos) << key;
  }
  EXPECT_NE(metrics.find("\"steps\": 150"), std::string::npos);
  EXPECT_NE(metrics.find("\"seed\": 3"), std::string::npos);
  // The trace holds the step's kernels (test_profiler.cpp checks its times).
  const std::string trace = test::read_text(dir.path("trace.json"));
  EXPECT_EQ(trace.substr(0, 2), "[\n");
  EXPECT_NE(trace.find("\"name\": \"sph_forces\""), std::string::npos);
  EXPECT_EQ(trace.substr(trace.size() - 2), "]\n");
  const Heightmap final_terrain = read_terrain(dir.path("out/final.asc"));
  EXPECT_EQ(final_terrain.nx, 65);
  // Progress goes to stderr as plain lines when it is not a terminal, and ends with a summary.
  EXPECT_NE(r.err.find("done:"), std::string::npos) << r.err;
}

TEST(CliRun, SameSeedGivesIdenticalTerrainBytes) {
  ScratchDir dir;
  for (const char* out : {"a", "b"}) {
    const auto r =
        run_cli({"run", "--generate", "cone", "--set", "terrain.size=49", "--steps", "200",
                 "--seed", "9", "--out", dir.path(out), "--quiet", "--set", "rain.rate=3000"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  EXPECT_EQ(test::read_text(dir.path("a/final.npy")), test::read_text(dir.path("b/final.npy")));
}

TEST(CliRun, BadValuesExitWithTwoNamingTheKey) {
  ScratchDir dir;
  test::write_text(dir.path("bad.toml"), "[rain]\nrate = 10\nbogus = 3\n");
  test::write_text(dir.path("negative.toml"), "[rain]\nrate = -5.0\n");
  struct Case {
    std::vector<std::string> args;
    const char* names;
  } cases[] = {
      {{"run", dir.path("bad.toml")}, "rain.bogus"},
      {{"run", dir.path("negative.toml")}, "rain.rate"},
      {{"run", "--set", "terrain.cell=0"}, "terrain.cell"},
      {{"run", "--set", "rain.intensity=-1"}, "rain.intensity"},
      {{"run", "--set", "erosion.model=magic"}, "erosion.model"},
      {{"run", "--set", "sph.cfl=0"}, "sph.cfl"},
      {{"run", "--terrain", dir.path("missing.asc")}, "missing.asc"},
      {{"run", "--steps", "10", "--sim-time", "3"}, "excludes"},
      {{"run", "--set", "rain.region=disc"}, "rain.disc_radius"},
      {{"run", "--steps", "5", "--trace", dir.path("no-folder/trace.json")}, "--trace"},
  };
  for (auto& c : cases) {
    auto args = c.args;
    args.push_back("--out");
    args.push_back(dir.path("never"));
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << c.names << ": " << r.err;
    EXPECT_NE(r.err.find(c.names), std::string::npos) << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.path("never/metrics.json")));
}

TEST(CliRun, RealDemWithItsOwnCellSizeRunsUnchanged) {
  ScratchDir dir;
  const auto r =
      run_cli({"run", "--terrain", test::source_dir() + "/data/terrains/jacksboro_fault_dem.asc",
               "--steps", "40", "--out", dir.path("dem"), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string metrics = test::read_text(dir.path("dem/metrics.json"));
  EXPECT_NE(metrics.find("\"spacing_m\": 41.5"), std::string::npos)
      << "the particle spacing follows the DEM's 83 m cells (half a cell)";
  EXPECT_NE(metrics.find("\"mass_balance_abs\": 0"), std::string::npos);
}

}  // namespace
}  // namespace runnel
