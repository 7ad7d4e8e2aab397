// SPDX-License-Identifier: MIT
// Standing water and gauges from the command line: probes.csv as documented, and every bad body or
// gauge refused with its key named, exit 2, before anything runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <sstream>

#include "runnel/terrain/terrain_io.hpp"
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
      // A rectangle 1e-9 m wide is printed as such, not as [0.000000, 0.000000].
      {"[[water.bodies]]\nx0 = 0\nx1 = 1e-9\ny0 = 0\ny1 = 8\nlevel = 1\n",
       "the rectangle [0, 1e-09] x [0, 8] holds no vertex"},
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

// A water.depth raster is refused in one line, nothing written, when a value is no depth (NaN is
// named as a depth), when its shape differs from the terrain's (resampling would stretch it), or
// when it is georeferenced in the terrain's CRS but lies elsewhere; one of the terrain's shape at
// another resolution is resampled with a warning.
TEST(StandingWaterCli, AWaterDepthRasterOfAnotherShapePlaceOrValueIsRefusedInOneLine) {
  test::ScratchDir dir;
  Heightmap terrain(33, 33, 10.0, 5.0f);
  write_terrain(dir.path("t.asc"), terrain);
  auto depth = [&](const std::string& name, int nx, int ny, float value) {
    Heightmap d(nx, ny, 10.0, 0.1f);
    d.at(2, 2) = value;
    write_terrain(dir.path(name), d);
  };
  depth("ok.npy", 17, 17, 0.1f);
  depth("depth.asc", 33, 33, 0.1f);
  depth("wide.npy", 33, 17, 0.1f);
  depth("negative.npy", 17, 17, -1.0f);
  {  // NaN: written by hand, as no runnel writer writes it
    Heightmap d(33, 33, 10.0, 0.1f);
    write_terrain(dir.path("nan.npy"), d);
    std::string bytes = test::read_text(dir.path("nan.npy"));
    const float nan = std::numeric_limits<float>::quiet_NaN();
    bytes.replace(bytes.size() - sizeof(float), sizeof(float),
                  std::string(reinterpret_cast<const char*>(&nan), sizeof(float)));
    test::write_text(dir.path("nan.npy"), bytes);
  }
  auto run = [&](const std::string& terrain_file, const std::string& depth_file) {
    test::write_text(dir.path("s.toml"), "[terrain]\nfile = \"" + terrain_file +
                                             "\"\n[water]\ndepth = \"" + depth_file + "\"\n");
    std::filesystem::remove_all(dir.path("o"));
    return test::run_cli({"run", dir.path("s.toml"), "--model", "pipe", "--steps", "1", "--quiet",
                          "--out", dir.path("o")});
  };
  const std::pair<std::string, std::string> refused[] = {
      {"nan.npy", "water.depth nan"},
      {"wide.npy", "another shape"},
      {"negative.npy", "water.depth holds -1"},
  };
  for (const auto& [file, named] : refused) {
    const auto r = run(dir.path("t.asc"), dir.path(file));
    EXPECT_EQ(r.exit_code, 2) << file << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << file << r.err;
    EXPECT_NE(r.err.find(named), std::string::npos) << file << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path("o"))) << file;
  }
  const auto ok = run(dir.path("t.asc"), dir.path("ok.npy"));
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.err.find("resampled"), std::string::npos) << ok.err;

  if (test::run_program("gdal_translate", {"--version"}).exit_code != 0)
    GTEST_SKIP() << "gdal_translate not installed (scripts/setup.sh): the georeferenced case";
  for (const auto& [name, west] :
       {std::pair{"here.tif", "500000"}, std::pair{"far.tif", "505000"}}) {
    const std::string east = std::to_string(std::stoi(west) + 330);
    const auto g = test::run_program(
        "gdal_translate",
        {"-q", "-a_srs", "EPSG:32633", "-a_ullr", west, "4100330", east, "4100000",
         dir.path(std::string(name) == "here.tif" ? "t.asc" : "depth.asc"), dir.path(name)});
    ASSERT_EQ(g.exit_code, 0) << g.err;
  }
  const auto far = run(dir.path("here.tif"), dir.path("far.tif"));
  EXPECT_EQ(far.exit_code, 2) << far.err;
  EXPECT_NE(far.err.find("another place"), std::string::npos) << far.err;
  EXPECT_NE(far.err.find("505000"), std::string::npos) << far.err;
}

// A parameter set beyond an HDF5 attribute's 64 KiB (here 3,000 gauges) is kept in final.h5 and
// resumed from it, rather than the run failing at its end.
TEST(StandingWaterCli, AParameterSetOfThousandsOfGaugesIsKeptInTheCheckpoint) {
  test::ScratchDir dir;
  std::string scenario = kBasin;
  for (int k = 0; k < 3000; ++k)
    scenario += "[[probes]]\nname = \"gauge_" + std::to_string(k) +
                "\"\nx = " + std::to_string(1 + k % 7) + "\ny = " + std::to_string(1 + k / 7 % 7) +
                "\n";
  test::write_text(dir.path("s.toml"), scenario);
  auto r = test::run_cli({"run", dir.path("s.toml"), "--out", dir.path("o"), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::run_cli(
      {"resume", dir.path("o/final.h5"), "--steps", "2", "--out", dir.path("r"), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(test::read_text(dir.path("r/probes.csv")).find("gauge_2999"), std::string::npos);
}

// runnel compare checks every model before the first runs: standing water one of them cannot hold
// is refused at once, with nothing written.
TEST(StandingWaterCli, CompareRefusesAModelThatHoldsNoWaterBeforeAnyRuns) {
  test::ScratchDir dir;
  test::write_text(
      dir.path("s.toml"),
      std::string(kBasin) + "[[water.bodies]]\nx0 = 0\nx1 = 3\ny0 = 0\ny1 = 8\nlevel = 0.6\n");
  // Not quiet: a model that ran would have said so.
  const auto r = test::run_cli(
      {"compare", dir.path("s.toml"), "--models", "pipe,droplet", "--out", dir.path("c")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("the droplet model holds no standing water"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("compare: model"), std::string::npos) << "a model ran first: " << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("c")));
}

// A scenario refused for a bad gauge leaves an existing output folder as it was, --overwrite or
// not.
TEST(StandingWaterCli, ARefusedScenarioLeavesTheFolderItWouldOverwrite) {
  test::ScratchDir dir;
  test::write_text(dir.path("s.toml"), kBasin);
  ASSERT_EQ(test::run_cli({"run", dir.path("s.toml"), "--out", dir.path("o"), "--quiet"}).exit_code,
            0);
  const std::string before = test::read_text(dir.path("o/metrics.json"));
  test::write_text(dir.path("bad.toml"),
                   std::string(kBasin) + "[[probes]]\nname = \"g\"\nx = 1e9\ny = 4\n");
  const auto r = test::run_cli(
      {"run", dir.path("bad.toml"), "--overwrite", "--out", dir.path("o"), "--quiet"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("(1e+09, 4) lies off the terrain"), std::string::npos) << r.err;
  EXPECT_EQ(test::read_text(dir.path("o/metrics.json")), before);
  EXPECT_TRUE(std::filesystem::exists(dir.path("o/final.h5")));
}

}  // namespace
}  // namespace runnel
