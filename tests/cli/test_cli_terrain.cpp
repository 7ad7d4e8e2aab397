// SPDX-License-Identifier: MIT
// End to end through the runnel binary: exit codes, one-line errors, deterministic generation,
// conversion of a real DEM through every format.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "runnel/terrain/terrain_io.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::run_cli;
using test::ScratchDir;

int line_count(const std::string& s) {
  return static_cast<int>(std::count(s.begin(), s.end(), '\n'));
}

TEST(Cli, VersionAndHelp) {
  auto r = run_cli({"--version"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("runnel "), std::string::npos);
  for (const char* sub : {"generate", "convert", "devices", "info", "params"}) {
    r = run_cli({sub, "--help"});
    EXPECT_EQ(r.exit_code, 0) << sub;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << sub;
  }
  EXPECT_NE(run_cli({"generate", "--help"}).out.find("diamond-square"), std::string::npos);
}

TEST(Cli, UsageErrorsExitWithTwo) {
  for (std::vector<std::string> args :
       std::vector<std::vector<std::string>>{{},
                                             {"frobnicate"},
                                             {"generate", "fbm"},
                                             {"generate", "fbm", "-o", "x.asc", "--bogus"},
                                             {"generate", "fbm", "--size", "abc", "-o", "x.asc"},
                                             {"devices", "--device"}}) {
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << (args.empty() ? "" : args[0]) << ": " << r.err;
    EXPECT_FALSE(r.err.empty());
  }
}

TEST(Cli, GenerateIsDeterministic) {
  ScratchDir dir;
  const auto a = run_cli(
      {"generate", "diamond-square", "--size", "257", "--seed", "7", "-o", dir.path("a.asc")});
  const auto b = run_cli(
      {"generate", "diamond-square", "--size", "257", "--seed", "7", "-o", dir.path("b.asc")});
  const auto c = run_cli(
      {"generate", "diamond-square", "--size", "257", "--seed", "8", "-o", dir.path("c.asc")});
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const std::string bytes = test::read_text(dir.path("a.asc"));
  EXPECT_EQ(bytes, test::read_text(dir.path("b.asc")));
  EXPECT_NE(bytes, test::read_text(dir.path("c.asc")));
  EXPECT_EQ(read_terrain(dir.path("a.asc")).nx, 257);
}

TEST(Cli, GenerateFromScenarioWithSet) {
  ScratchDir dir;
  const auto r =
      run_cli({"generate", "--scenario", test::source_dir() + "/data/scenarios/default.toml",
               "--size", "65", "--set", "octaves=3", "-o", dir.path("s.npy")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_terrain(dir.path("s.npy")).nx, 65);
  const auto bad = run_cli({"generate", "fbm", "--set", "octaves=99", "-o", dir.path("bad.npy")});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("octaves"), std::string::npos);
}

TEST(Cli, RealDemConvertsThroughEveryFormat) {
  ScratchDir dir;
  const std::string dem = test::source_dir() + "/data/terrains/jacksboro_fault_dem.asc";
  const Heightmap original = read_terrain(dem);
  ASSERT_EQ(run_cli({"convert", dem, dir.path("d.png")}).exit_code, 0);
  ASSERT_EQ(run_cli({"convert", dir.path("d.png"), dir.path("from_png.asc")}).exit_code, 0);
  ASSERT_EQ(run_cli({"convert", dem, dir.path("d.npy")}).exit_code, 0);
  ASSERT_EQ(
      run_cli({"convert", dir.path("d.npy"), dir.path("from_npy.asc"), "--cell", "83"}).exit_code,
      0);
  const Heightmap from_png = read_terrain(dir.path("from_png.asc"));
  const Heightmap from_npy = read_terrain(dir.path("from_npy.asc"));
  const double quantum = (original.max_height() - original.min_height()) / 65535.0;
  ASSERT_EQ(from_png.size(), original.size());
  for (std::size_t k = 0; k < original.size(); ++k) {
    ASSERT_NEAR(from_png.h[k], original.h[k], 0.5 * quantum + 1e-3);
    ASSERT_EQ(from_npy.h[k], original.h[k]);
  }
  EXPECT_DOUBLE_EQ(from_png.cell, 83.0);
  EXPECT_DOUBLE_EQ(from_npy.cell, 83.0);
  // A given range quantises into it.
  ASSERT_EQ(run_cli({"convert", dem, dir.path("r.png"), "--range", "0:2000"}).exit_code, 0);
  const Heightmap ranged = read_terrain(dir.path("r.png"));
  EXPECT_NEAR(ranged.max_height(), original.max_height(), 2000.0 / 65535.0);
}

TEST(Cli, BadTerrainGivesExitTwoAndOneLineNothingOverwritten) {
  ScratchDir dir;
  const std::string header = "ncols 4\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 1\n";
  test::write_text(dir.path("truncated.asc"), header + "1 2 3 4\n5 6\n");
  test::write_text(dir.path("words.asc"), header + "1 2 3 4\n5 6 x 8\n9 1 2 3\n");
  test::write_text(dir.path("out.png"), "precious");
  for (const char* name : {"truncated.asc", "words.asc", "missing.asc"}) {
    const auto r = run_cli({"convert", dir.path(name), dir.path("out.png")});
    EXPECT_EQ(r.exit_code, 2) << name;
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(name), std::string::npos) << r.err;
    EXPECT_EQ(test::read_text(dir.path("out.png")), "precious");
  }
  const auto r = run_cli({"convert", dir.path("words.asc"), dir.path("out.xyz")});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("out.xyz"), std::string::npos);
}

TEST(Cli, DevicesListsPoclAndBadDeviceEnvIsAnError) {
  auto r = run_cli({"devices"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("CPU"), std::string::npos);
  EXPECT_NE(r.out.find("compute units"), std::string::npos);
  r = run_cli({"devices", "--json"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("\"compute_units\""), std::string::npos);
  r = run_cli({"devices"}, "RUNNEL_DEVICE=no-such-device");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no-such-device"), std::string::npos);
}

TEST(Cli, NoOpenClDriverIsAClearError) {
  // An empty vendor folder hides every ICD from the loader: the same as a machine with no driver.
  ScratchDir dir;
  const auto r = run_cli({"devices"},
                         "OCL_ICD_VENDORS=" + dir.path("") + " OPENCL_VENDOR_PATH=" + dir.path(""));
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("pocl-opencl-icd"), std::string::npos) << r.err;
}

TEST(Cli, InfoDescribesATerrain) {
  const auto r =
      run_cli({"info", "--json", test::source_dir() + "/data/terrains/jacksboro_fault_dem.asc"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"nx\": 403"), std::string::npos) << r.out;
  // Stored in whole metres: a staircase (docs/terrain-formats.md, "Stepped DEMs").
  EXPECT_EQ(test::json_number(r.out, "height_step"), 1.0) << r.out;
  EXPECT_NE(r.out.find("\"stepped\": true"), std::string::npos) << r.out;
  const auto png = run_cli({"info", test::source_dir() + "/data/terrains/fbm_257.png"});
  ASSERT_EQ(png.exit_code, 0) << png.err;
  EXPECT_EQ(png.out.find("stepped"), std::string::npos) << png.out;
}

}  // namespace
}  // namespace runnel
