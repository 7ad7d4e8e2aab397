// SPDX-License-Identifier: MIT
// outflow.csv, the water's budget through a run: that it balances, that the rain in it is the rain
// that fell, that the edges are told apart, and that a resumed run writes what the uninterrupted
// one writes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "runnel/core/error.hpp"
#include "runnel/core/parameters_toml.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/sim/run.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

// A plane falling to the east (x), with a ridge across it, 33 × 17 cells of 1 m.
Heightmap tilted_plane() {
  Heightmap t(33, 17, 1.0);
  for (int j = 0; j < t.ny; ++j)
    for (int i = 0; i < t.nx; ++i) t.at(i, j) = static_cast<float>(0.05 * (t.nx - 1 - i) + 1.0);
  return t;
}

Parameters scenario(const std::string& toml) {
  Parameters p = default_parameters();
  read_parameters_toml(p, toml, "test");
  return p;
}

struct Row {
  double t, rain, outflow, stored, rain_volume, outflow_volume;
  std::vector<double> edges;
};

std::vector<Row> read_rows(const std::string& path) {
  std::istringstream in(test::read_text(path));
  std::string line;
  std::getline(in, line);  // header
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) v.push_back(std::stod(cell));
    rows.push_back({v[0], v[1], v[2], v[3], v[4], v[5], {v.begin() + 6, v.end()}});
  }
  return rows;
}

RunOptions options_into(const std::string& dir, std::uint64_t until_step) {
  RunOptions o;
  o.out_dir = dir;
  o.quiet = true;
  o.until_step = until_step;
  return o;
}

TEST(Hydrograph, ThePipeModelsBudgetBalancesAndItsRainIsTheRainThatFell) {
  test::ScratchDir dir;
  const double rain = 1e-3;  // m/s on 33 × 17 cells of 1 m²
  Parameters p = scenario(
      "[run]\nmodel = \"pipe\"\noutflow_every = 0.5\noutflow_edges = true\n"
      "[pipe]\nrain = 0.001\nevaporation = 0\ncapacity = 0\nflux = \"godunov\"\nmanning_n = "
      "0.05\n");
  std::unique_ptr<Model> model = make_model(compute(), p, tilted_plane());
  RunOptions o = options_into(dir.path("run"), 0);
  o.until_time = 30;
  run_model(compute(), *model, o);
  const std::vector<Row> rows = read_rows(dir.path("run/outflow.csv"));
  ASSERT_GE(rows.size(), 59u);
  const double area = 33.0 * 17.0;
  double previous_t = 0;
  for (const Row& r : rows) {
    // The rain rate is the scenario's over the whole map, the volume its integral.
    EXPECT_NEAR(r.rain, rain * area, 1e-9 * rain * area) << r.t;
    EXPECT_NEAR(r.rain_volume, rain * area * r.t, 1e-9 * rain * area * r.t) << r.t;
    // What fell is on the terrain or has left it (float depths: to a few 10⁻⁶).
    EXPECT_NEAR(r.rain_volume - r.outflow_volume - r.stored, 0.0, 1e-5 * r.rain_volume) << r.t;
    // The edges add up to the outflow; water runs east, and the closed-by-nothing sides let some
    // out too, but none climbs the slope out of the west edge faster than rain falls there.
    ASSERT_EQ(r.edges.size(), 4u);
    EXPECT_NEAR(r.edges[0] + r.edges[1] + r.edges[2] + r.edges[3], r.outflow, 1e-6 * rain * area);
    EXPECT_GE(r.t, previous_t + 0.5 - 1e-9);
    previous_t = r.t;
  }
  const Row& last = rows.back();
  EXPECT_GT(last.edges[1], 5 * last.edges[0]);  // the east (downhill) edge carries the most
  EXPECT_GT(last.outflow, 0.3 * rain * area);
}

TEST(Hydrograph, AResumedRunWritesTheRowsTheUninterruptedRunWrites) {
  for (const char* model_name : {"pipe", "sph"}) {
    test::ScratchDir dir;
    Parameters p = scenario(std::string("[run]\nmodel = \"") + model_name +
                            "\"\noutflow_every = 0.05\n[pipe]\nrain = 0.002\nevaporation = 0\n"
                            "[sph]\nspacing = 0.5\n[rain]\nintensity = 200000\n");
    std::unique_ptr<Model> whole = make_model(compute(), p, tilted_plane());
    run_model(compute(), *whole, options_into(dir.path("whole"), 60));
    std::unique_ptr<Model> first = make_model(compute(), p, tilted_plane());
    RunOptions o = options_into(dir.path("first"), 60);
    o.checkpoint_every = 25;
    run_model(compute(), *first, o);
    const CheckpointData mid = read_checkpoint(dir.path("first/checkpoints/step_00000025.h5"));
    std::unique_ptr<Model> resumed = make_model_from_checkpoint(compute(), mid);
    RunOptions r = options_into(dir.path("resumed"), 60);
    r.resumed_counters = mid.model_counters;
    run_model(compute(), *resumed, r);
    const std::string all = test::read_text(dir.path("whole/outflow.csv"));
    const std::string tail = test::read_text(dir.path("resumed/outflow.csv"));
    std::istringstream tail_lines(tail);
    std::string header, first_row;
    std::getline(tail_lines, header);
    std::getline(tail_lines, first_row);
    ASSERT_FALSE(first_row.empty()) << model_name;
    // The resumed rows are the uninterrupted run's from the first row after the checkpoint on.
    const std::size_t at = all.find(first_row);
    ASSERT_NE(at, std::string::npos) << model_name << ": " << first_row;
    EXPECT_EQ(all.substr(at), tail.substr(header.size() + 1)) << model_name;
    EXPECT_GT(read_rows(dir.path("whole/outflow.csv")).back().rain_volume, 0) << model_name;
  }
}

TEST(Hydrograph, SphCountsItsOutflowOverAllEdgesTogether) {
  test::ScratchDir dir;
  Parameters p = scenario("[run]\nmodel = \"sph\"\noutflow_edges = true\n[sph]\nspacing = 0.5\n");
  std::unique_ptr<Model> model = make_model(compute(), p, tilted_plane());
  try {
    run_model(compute(), *model, options_into(dir.path("run"), 2));
    FAIL() << "run.outflow_edges was accepted for sph";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kUsage);
    EXPECT_NE(std::string(e.what()).find("run.outflow_edges"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir.path("run")));  // refused before the folder is made
}

TEST(Hydrograph, ModelsWithoutAFlowOfWaterWriteNone) {
  test::ScratchDir dir;
  Parameters p = scenario("[run]\nmodel = \"thermal\"\n");
  std::unique_ptr<Model> model = make_model(compute(), p, tilted_plane());
  run_model(compute(), *model, options_into(dir.path("run"), 3));
  EXPECT_FALSE(std::filesystem::exists(dir.path("run/outflow.csv")));
  EXPECT_TRUE(std::filesystem::exists(dir.path("run/metrics.json")));
}

}  // namespace
}  // namespace runnel
