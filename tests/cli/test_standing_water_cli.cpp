// SPDX-License-Identifier: MIT
// Standing water and gauges from the command line: probes.csv as documented, and every bad body or
// gauge refused with its key named, exit 2, before anything runs.
#include <gtest/gtest.h>

#include <sstream>

#include "test_support.hpp"

namespace runnel {
namespace {

const char* kBasin =
    "[terrain]\ngenerator = \"plane\"\nsize = 33\ncell = 0.25\n"
    "[run]\nmodel = \"pipe\"\nsim_time = 1.0\nprobe_every = 0.25\n"
    "[pipe]\nrain = 0\n";

TEST(StandingWaterCli, APipeRunWritesItsGaugesReadings) {
  test::ScratchDir dir;
  test::write_text(dir.path("s.toml"),
                   std::string(kBasin) +
                       "[[water.bodies]]\nx0 = 0\nx1 = 3\ny0 = 0\ny1 = 8\nlevel = 0.6\n"
                       "[[probes]]\nname = \"up\"\nx = 1\ny = 4\n"
                       "[[probes]]\nname = \"down\"\nx = 6\ny = 4\n");
  const auto r = test::run_cli({"run", dir.path("s.toml"), "--out", dir.path("o"), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream csv(test::read_text(dir.path("o/probes.csv")));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "t,name,surface,depth,bed");
  int rows = 0;
  double last_t = -1;
  while (std::getline(csv, line)) {
    double t = 0;
    char name[16] = {0};
    double surface = 0, depth = 0, bed = 0;
    ASSERT_EQ(
        std::sscanf(line.c_str(), "%lf,%15[^,],%lf,%lf,%lf", &t, name, &surface, &depth, &bed), 5)
        << line;
    EXPECT_GE(t, last_t);
    EXPECT_GE(depth, 0.0);
    EXPECT_NEAR(surface, bed + depth, 2e-6) << line;
    if (rows == 0) {
      EXPECT_GT(depth, 0.05) << "the reservoir gauge starts under water";
    }
    last_t = t;
    ++rows;
  }
  EXPECT_EQ(rows, 2 * 5);  // t = 0, 0.25, 0.5, 0.75, 1.0
  EXPECT_NE(test::read_text(dir.path("o/metrics.json")).find("\"initial_water_volume\": "),
            std::string::npos);
}

TEST(StandingWaterCli, BadBodiesAndGaugesAreRefusedWithTheirKeys) {
  struct Case {
    std::string scenario, named;
  };
  const std::vector<Case> cases = {
      {"[[water.bodies]]\nx0 = 50\nx1 = 60\ny0 = 0\ny1 = 8\nlevel = 1\n", "water.bodies[1]"},
      {"[[water.bodies]]\nx0 = 3\nx1 = 1\ny0 = 0\ny1 = 8\nlevel = 1\n", "water.bodies[1]"},
      {"[[water.bodies]]\nx0 = 0\nx1 = 8\ny0 = 0\ny1 = 8\nlevel = -5\n", "water.bodies[1].level"},
      {"[[water.bodies]]\nx0 = 0\nx1 = 8\ny0 = 0\ny1 = 8\nlevel = 1\ndepth = 2\n",
       "water.bodies[1].depth"},
      {"[[probes]]\nname = \"g\"\nx = 90\ny = 4\n", "probes[1]"},
      {"[[probes]]\nname = \"g\"\nx = 1\ny = 4\n[[probes]]\nname = \"g\"\nx = 2\ny = 4\n",
       "probes[2].name"},
      {"[[probes]]\nname = \"a,b\"\nx = 1\ny = 4\n", "probes[1].name"},
      {"[water]\nbodies = 3\n", "water.bodies"},
  };
  for (const Case& c : cases) {
    test::ScratchDir dir;
    test::write_text(dir.path("s.toml"), std::string(kBasin) + c.scenario);
    const auto r = test::run_cli({"run", dir.path("s.toml"), "--out", dir.path("o"), "--quiet"});
    EXPECT_EQ(r.exit_code, 2) << c.scenario << r.err;
    EXPECT_NE(r.err.find(c.named), std::string::npos) << c.scenario << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path("o/metrics.json")));
  }
  test::ScratchDir dir;
  test::write_text(
      dir.path("s.toml"),
      std::string(kBasin) + "[[water.bodies]]\nx0 = 0\nx1 = 8\ny0 = 0\ny1 = 8\nlevel = 1\n");
  auto r = test::run_cli(
      {"run", dir.path("s.toml"), "--model", "thermal", "--out", dir.path("o"), "--quiet"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("water.bodies: the thermal model holds no standing water"),
            std::string::npos)
      << r.err;
  r = test::run_cli(
      {"run", dir.path("s.toml"), "--set", "water.bodies=1", "--out", dir.path("o"), "--quiet"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("[[water.bodies]]"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace runnel
