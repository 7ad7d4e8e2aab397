// SPDX-License-Identifier: MIT
// The comparison models through the command line: `runnel run --model`, scenario files choosing
// a model, resuming a grid model exactly, and `runnel compare` with its table, figure and report.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "runnel/metrics/terrain_metrics.hpp"
#include "runnel/terrain/terrain_io.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::json_number;
using test::run_cli;
using test::ScratchDir;

const std::vector<std::string> kSmallTerrain = {"--generate",      "fbm",   "--set",
                                                "terrain.size=49", "--set", "terrain.cell=2"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

TEST(CliModels, RunEveryGridModelWithItsMetrics) {
  ScratchDir dir;
  for (const char* model : {"droplet", "pipe", "olsen", "thermal"}) {
    const std::string out = dir.path(model);
    const auto r = run_cli(
        with({"run", "--model", model, "--steps", "20", "--out", out, "--quiet"}, kSmallTerrain));
    ASSERT_EQ(r.exit_code, 0) << model << ": " << r.err;
    const std::string m = test::read_text(out + "/metrics.json");
    EXPECT_NE(m.find(std::string("\"model\": \"") + model + "\""), std::string::npos) << model;
    EXPECT_EQ(json_number(m, "steps"), 20.0) << model;
    EXPECT_EQ(json_number(m, "mass_balance_abs"), 0.0) << model;
    EXPECT_GT(json_number(m, "eroded_volume"), 0.0) << model;
    EXPECT_NE(m.find("\"hypsometric_integral\""), std::string::npos) << model;
    EXPECT_NE(m.find("\"kernel_seconds\""), std::string::npos) << model;
    for (const char* f : {"erosion.png", "final.h5", "final.npy", "drainage_area.npy"})
      EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << model << " " << f;
  }
}

TEST(CliModels, ARunOfAGivenTimeEndsOnItWhateverTheLargestStep) {
  // A step limit far longer than the run: the last step is cut to the run's end, so the pipe model
  // rains for 0.01 s (pipe.rain on 49 × 49 cells of 4 m²), not for the 5 s step it would take.
  ScratchDir dir;
  const auto pipe = run_cli(with({"run", "--model", "pipe", "--set", "pipe.dt_max=5", "--sim-time",
                                  "0.01", "--out", dir.path("pipe"), "--quiet"},
                                 kSmallTerrain));
  ASSERT_EQ(pipe.exit_code, 0) << pipe.err;
  const std::string m = test::read_text(dir.path("pipe/metrics.json"));
  EXPECT_NEAR(json_number(m, "sim_time"), 0.01, 1e-12);
  EXPECT_NEAR(json_number(m, "rain_volume"), 0.01 * 49 * 49 * 4 * 0.01, 1e-6);
  const auto sph =
      run_cli(with({"run", "--model", "sph", "--set", "sph.solver=dfsph", "--set", "sph.dt_max=5",
                    "--sim-time", "1", "--out", dir.path("sph"), "--quiet"},
                   kSmallTerrain));
  ASSERT_EQ(sph.exit_code, 0) << sph.err;
  EXPECT_NEAR(json_number(test::read_text(dir.path("sph/metrics.json")), "sim_time"), 1.0, 1e-9);
}

TEST(CliModels, DrainageAreaMapIsTheFinalTerrainsFlowAccumulation) {
  ScratchDir dir;
  ASSERT_EQ(
      run_cli(with({"run", "--model", "thermal", "--steps", "5", "--out", dir.path("t"), "--quiet"},
                   kSmallTerrain))
          .exit_code,
      0);
  Heightmap final_terrain = read_terrain(dir.path("t/final.npy"));  // the exact float heights
  final_terrain.cell = 2.0;                                         // NPY has no cell size
  const Heightmap area = read_terrain(dir.path("t/drainage_area.npy"));
  ASSERT_EQ(area.size(), final_terrain.size());
  // Every vertex drains at least its own cell; the border outlets together drain the whole map.
  const double cell2 = 2.0 * 2.0;
  double outlets = 0;
  for (int j = 0; j < area.ny; ++j) {
    for (int i = 0; i < area.nx; ++i) {
      EXPECT_GE(area.at(i, j), cell2 * (1 - 1e-6));
      if (i == 0 || j == 0 || i == area.nx - 1 || j == area.ny - 1) outlets += area.at(i, j);
    }
  }
  // Border vertices may also drain into one another, so their sum is at least the map's area.
  EXPECT_GE(outlets, area.size() * cell2 * (1 - 1e-6));
  const std::vector<double> reference = metrics::flow_accumulation(final_terrain);
  for (std::size_t k = 0; k < reference.size(); ++k)
    ASSERT_FLOAT_EQ(area.h[k], static_cast<float>(reference[k])) << k;
}

TEST(CliModels, ScenarioFileChoosesTheModelAndItsClock) {
  ScratchDir dir;
  test::write_text(dir.path("olsen.toml"),
                   "[terrain]\ngenerator = \"fbm\"\nsize = 33\n[run]\nmodel = \"olsen\"\n"
                   "iterations = 12\n");
  const auto r = run_cli({"run", dir.path("olsen.toml"), "--out", dir.path("o"), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string m = test::read_text(dir.path("o/metrics.json"));
  EXPECT_NE(m.find("\"model\": \"olsen\""), std::string::npos);
  EXPECT_EQ(json_number(m, "steps"), 12.0) << "olsen counts run.iterations";
  EXPECT_NE(m.find("\"clock\": \"iterations\""), std::string::npos);
}

TEST(CliModels, OneScenarioGivesSecondsToTheRainAndYearsToTheLandscape) {
  ScratchDir dir;
  test::write_text(dir.path("both.toml"),
                   "[terrain]\ngenerator = \"fbm\"\nsize = 33\ncell = 50.0\n"
                   "[stream_power]\ndt = 1000.0\n[rain]\nrate = 50.0\nmax_particles = 500\n"
                   "[run]\nsim_time = 2.0\nsim_years = 5000.0\n");
  auto steps = [&](const std::string& folder) {
    return json_number(test::read_text(dir.path(folder + "/metrics.json")), "steps");
  };
  auto run = [&](std::vector<std::string> args) {
    const auto r = run_cli(std::move(args));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  };
  run({"run", dir.path("both.toml"), "--model", "stream-power", "--out", dir.path("sp"),
       "--quiet"});
  EXPECT_EQ(steps("sp"), 5.0) << "run.sim_years / stream_power.dt";
  run({"run", dir.path("both.toml"), "--model", "stream-power", "--sim-time", "3000", "--out",
       dir.path("flag"), "--quiet"});
  EXPECT_EQ(steps("flag"), 3.0) << "--sim-time wins over the scenario's years";
  run({"compare", dir.path("both.toml"), "--models", "pipe,stream-power", "--out", dir.path("cmp"),
       "--quiet"});
  EXPECT_EQ(steps("cmp/stream-power"), 5.0);
  const std::string pipe = test::read_text(dir.path("cmp/pipe/metrics.json"));
  EXPECT_NEAR(json_number(pipe, "sim_time"), 2.0, 0.05) << "the rain model keeps run.sim_time";
}

TEST(CliModels, TheShippedUpliftScenarioGrowsADrainageNetwork) {
  ScratchDir dir;
  const auto r = run_cli({"run", test::source_dir() + "/data/scenarios/uplift.toml", "--out",
                          dir.path("u"), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string m = test::read_text(dir.path("u/metrics.json"));
  EXPECT_EQ(json_number(m, "steps"), 1000.0) << "1 Myr in steps of 1000 yr";
  EXPECT_EQ(json_number(m, "mass_balance_abs"), 0.0);
  // A plateau of 32 m roughness becomes a dissected range hundreds of metres high, its channels
  // near the steady state's concavity m/n = 0.5 (diffusion bends the smallest catchments).
  const Heightmap final_terrain = read_terrain(dir.path("u/final.npy"));
  EXPECT_GT(final_terrain.max_height() - final_terrain.min_height(), 10 * 32.0);
  EXPECT_GT(json_number(m, "channel_nodes"), 1000.0);
  EXPECT_NEAR(json_number(m, "concavity_theta"), 0.5, 0.15);
  const auto info = run_cli({"info", dir.path("u/final.h5"), "--json"});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NEAR(json_number(info.out, "uplift_volume"), json_number(m, "uplift_volume_m3"),
              1e-6 * json_number(m, "uplift_volume_m3"))
      << "runnel info reports the uplift its eroded and deposited figures include";
}

TEST(CliModels, ResumedPipeRunEqualsTheUninterruptedOne) {
  ScratchDir dir;
  const auto base = with({"--model", "pipe", "--quiet"}, kSmallTerrain);
  ASSERT_EQ(run_cli(with({"run", "--steps", "60", "--out", dir.path("straight")}, base)).exit_code,
            0);
  ASSERT_EQ(run_cli(with({"run", "--steps", "30", "--out", dir.path("first")}, base)).exit_code, 0);
  const auto r = run_cli({"resume", dir.path("first/final.h5"), "--steps", "30", "--out",
                          dir.path("second"), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::read_text(dir.path("straight/final.npy")),
            test::read_text(dir.path("second/final.npy")));
  const std::string m = test::read_text(dir.path("second/metrics.json"));
  EXPECT_NE(m.find("\"model\": \"pipe\""), std::string::npos);
  EXPECT_EQ(json_number(m, "resumed_from_step"), 30.0);
  // runnel info reads a grid model's checkpoint: its fields and the sediment they carry.
  const auto info = run_cli({"info", dir.path("first/final.h5"), "--json"});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("\"model\": \"pipe\""), std::string::npos);
  EXPECT_NE(info.out.find("sediment__suspended"), std::string::npos) << info.out;
  EXPECT_NEAR(json_number(info.out, "suspended_volume"),
              json_number(test::read_text(dir.path("first/metrics.json")), "suspended_volume"),
              1e-9);
}

TEST(CliModels, UnknownModelOrWrongClockExitsWithTwo) {
  ScratchDir dir;
  const auto r = run_cli(
      with({"run", "--model", "lava", "--steps", "5", "--out", dir.path("x")}, kSmallTerrain));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("lava"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("x")));
  const auto seconds = run_cli(
      with({"run", "--model", "olsen", "--sim-time", "5", "--out", dir.path("x")}, kSmallTerrain));
  EXPECT_EQ(seconds.exit_code, 2);
  EXPECT_NE(seconds.err.find("--sim-time"), std::string::npos) << seconds.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("x")));
}

// metrics.csv as rows of cells.
std::vector<std::vector<std::string>> read_csv(const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(test::read_text(path));
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::istringstream l(line);
    for (std::string c; std::getline(l, c, ',');) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}

TEST(CliModels, CompareWritesTableFigureAndReportWithOneRainBudget) {
  ScratchDir dir;
  test::write_text(dir.path("small.toml"),
                   "[terrain]\ngenerator = \"fbm\"\nsize = 49\ncell = 2.0\n[run]\nsim_time = 2.0\n"
                   "iterations = 20\n[rain]\nrate = 300.0\nmax_particles = 2000\n");
  const auto r = run_cli({"compare", dir.path("small.toml"), "--models",
                          "sph,droplet,pipe,olsen,thermal", "--out", dir.path("cmp"), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = read_csv(dir.path("cmp/metrics.csv"));
  ASSERT_EQ(rows.size(), 6u) << "a header and a row per model";
  const auto& header = rows[0];
  auto column = [&](const std::string& name) {
    for (std::size_t k = 0; k < header.size(); ++k)
      if (header[k] == name) return k;
    ADD_FAILURE() << "no column " << name;
    return std::size_t{0};
  };
  const std::size_t rain = column("rain_volume_m3"), balance = column("mass_balance_abs_m3"),
                    eroded = column("eroded_volume_m3");
  column("hypsometric_integral");
  column("spectral_slope");
  column("erosion_flow_correlation");
  const std::size_t roughening = column("short_wavelength_power_ratio");
  // The budget: 300 particles/s of (1 m)³ (half the 2 m cell) for 2 s.
  const double budget = 300.0 * 1.0 * 2.0;
  const char* models[] = {"sph", "droplet", "pipe", "olsen", "thermal"};
  for (std::size_t k = 1; k < rows.size(); ++k) {
    ASSERT_EQ(rows[k].size(), header.size());
    EXPECT_EQ(rows[k][0], models[k - 1]);
    EXPECT_EQ(std::stod(rows[k][balance]), 0.0) << rows[k][0];
    EXPECT_GT(std::stod(rows[k][eroded]), 0.0) << rows[k][0];
    const double v = std::stod(rows[k][rain]);
    if (rows[k][0] == "thermal")
      EXPECT_EQ(v, 0.0);
    else
      EXPECT_NEAR(v, budget, 0.03 * budget) << rows[k][0] << " receives the same rain";
    EXPECT_TRUE(std::filesystem::exists(dir.path("cmp/" + rows[k][0] + "/metrics.json")));
    const double ratio = std::stod(rows[k][roughening]);
    EXPECT_TRUE(std::isfinite(ratio) && ratio > 0) << rows[k][0];
    // Talus only moves height from a vertex to its lower neighbours: it smooths (0.40 here).
    if (rows[k][0] == "thermal") {
      EXPECT_LT(ratio, 1.0);
    }
  }
  const std::string png = test::read_text(dir.path("cmp/compare.png"));
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  const std::string report = test::read_text(dir.path("cmp/report.md"));
  EXPECT_NE(report.find("!["), std::string::npos);
  EXPECT_NE(report.find("(compare.png)"), std::string::npos);
  // The hydrograph of the models whose clock is in seconds (sph, pipe), each from its outflow.csv,
  // whose rain adds up to the budget it received.
  EXPECT_NE(report.find("`python -m runnel plot DIR`"), std::string::npos) << report;
  for (const char* model : {"sph", "pipe"}) {
    const std::string csv = test::read_text(dir.path(std::string("cmp/") + model + "/outflow.csv"));
    const std::size_t last = csv.rfind('\n', csv.size() - 2) + 1;
    std::vector<double> cells;
    std::istringstream line(csv.substr(last));
    for (std::string cell; std::getline(line, cell, ',');) cells.push_back(std::stod(cell));
    ASSERT_EQ(cells.size(), 6u) << model;
    EXPECT_NEAR(cells[4], budget, 0.03 * budget) << model << ": rain_volume at the end";
  }
  for (const char* m : models)
    EXPECT_NE(report.find(std::string("| [") + m + "]"), std::string::npos) << m;
  EXPECT_NE(report.find("- pipe: pipe.rain = "), std::string::npos) << "how pipe got its rain";
  EXPECT_NE(report.find("short-λ power after/before"), std::string::npos);
}

TEST(CliModels, CompareRefusesBadModelListsBeforeWritingAnything) {
  ScratchDir dir;
  for (const char* list : {"sph,lava", "pipe,pipe", "pipe,,olsen"}) {
    const auto r = run_cli(
        {"compare", "--models", list, "--set", "terrain.size=17", "--out", dir.path("cmp")});
    EXPECT_EQ(r.exit_code, 2) << list;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path("cmp"))) << list;
  }
  const auto steps = run_cli({"compare", "--models", "pipe", "--set", "terrain.size=17", "--set",
                              "run.steps=10", "--out", dir.path("cmp")});
  EXPECT_EQ(steps.exit_code, 2);
  EXPECT_NE(steps.err.find("run.steps"), std::string::npos) << steps.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("cmp")));
}

}  // namespace
}  // namespace runnel
