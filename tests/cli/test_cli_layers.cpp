// SPDX-License-Identifier: MIT
// Layered ground through the command line (docs/layers.md): a layered run's outputs, generate's
// per-layer rasters read back as thickness files, info's table, and bad layer input refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "runnel/terrain/terrain_io.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::json_number;
using test::run_cli;
using test::ScratchDir;

const char* kTerrain =
    "[terrain]\ngenerator = \"fbm\"\nsize = 49\ncell = 2.0\nseed = 7\n[terrain.set]\nrelief = "
    "0.2\n";

const char* kDippingLayers =
    "[[layers]]\nname = \"sand\"\ndepth = 2.0\ndip = 10\nstrike = 45\nerodibility = 2\n"
    "[[layers]]\nname = \"shale\"\ndepth = 4.0\ndip = 10\nstrike = 45\nerodibility = 0.5\n"
    "[ground]\nbedrock_name = \"granite\"\nbedrock_erodibility = 0.1\n";

TEST(CliLayers, ALayeredRunWritesItsMapsAndReportsEveryLayer) {
  ScratchDir dir;
  test::write_text(dir.path("s.toml"), std::string(kTerrain) + kDippingLayers);
  const std::string out = dir.path("run");
  const auto r = run_cli(
      {"run", dir.path("s.toml"), "--model", "pipe", "--sim-time", "2", "--out", out, "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string m = test::read_text(out + "/metrics.json");
  EXPECT_EQ(json_number(m, "layer_balance_quanta"), 0.0);
  EXPECT_EQ(json_number(m, "mass_balance_abs"), 0.0);
  for (const char* name : {"\"sand\"", "\"shale\"", "\"granite\"", "\"sediment\""})
    EXPECT_NE(m.find(name), std::string::npos) << name;
  for (const char* f : {"geology.png", "exposed_layer.tif", "exposed_layer.npy",
                        "sediment_thickness.tif", "final.h5"})
    EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
  // The exposed map holds material indices 0..3 and all three rocks crop out.
  const Heightmap exposed = read_terrain(out + "/exposed_layer.npy");
  int seen[4] = {0, 0, 0, 0};
  for (float v : exposed.h) {
    ASSERT_TRUE(v == 0 || v == 1 || v == 2 || v == 3) << v;
    ++seen[static_cast<int>(v)];
  }
  for (int m_index = 0; m_index < 3; ++m_index) EXPECT_GT(seen[m_index], 0) << m_index;
  const auto info = run_cli({"info", out + "/final.h5"});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("layer stack"), std::string::npos);
  EXPECT_NE(info.out.find("granite"), std::string::npos);
}

TEST(CliLayers, GeneratedLayerRastersReadBackAsTheSameStack) {
  ScratchDir dir;
  test::write_text(dir.path("s.toml"), std::string(kTerrain) + kDippingLayers);
  const auto g = run_cli({"generate", "--scenario", dir.path("s.toml"), "-o", dir.path("t.tif")});
  ASSERT_EQ(g.exit_code, 0) << g.err;
  ASSERT_TRUE(std::filesystem::exists(dir.path("t.sand.tif")));
  ASSERT_TRUE(std::filesystem::exists(dir.path("t.shale.tif")));
  test::write_text(dir.path("r.toml"),
                   "[terrain]\nfile = \"t.tif\"\n"
                   "[[layers]]\nname = \"sand\"\nthickness_file = \"t.sand.tif\"\nerodibility = 2\n"
                   "[[layers]]\nname = \"shale\"\nthickness_file = \"t.shale.tif\"\n"
                   "erodibility = 0.5\n[ground]\nbedrock_name = \"granite\"\n"
                   "bedrock_erodibility = 0.1\n");
  for (const char* s : {"s", "r"}) {
    const auto r = run_cli({"run", dir.path(std::string(s) + ".toml"), "--model", "thermal",
                            "--steps", "1", "--out", dir.path(std::string("out_") + s), "--quiet"});
    ASSERT_EQ(r.exit_code, 0) << s << ": " << r.err;
  }
  const Heightmap a = read_terrain(dir.path("out_s/exposed_layer.npy"));
  const Heightmap b = read_terrain(dir.path("out_r/exposed_layer.npy"));
  ASSERT_EQ(a.size(), b.size());
  std::size_t differ = 0;
  for (std::size_t k = 0; k < a.size(); ++k) differ += a.h[k] != b.h[k];
  // Float32 thickness rasters round a contact by at most a quantum or two.
  EXPECT_LE(differ, a.size() / 200) << "of " << a.size();
  // One HDF5 file with the stack.
  const auto h = run_cli({"generate", "--scenario", dir.path("s.toml"), "-o", dir.path("t.h5")});
  ASSERT_EQ(h.exit_code, 0) << h.err;
  EXPECT_TRUE(std::filesystem::exists(dir.path("t.h5")));
}

TEST(CliLayers, CompareShowsEveryModelsGeologyAndLayerVolumes) {
  ScratchDir dir;
  test::write_text(dir.path("s.toml"),
                   std::string(kTerrain) + kDippingLayers + "[run]\nsim_time = 1.0\n");
  const auto r = run_cli({"compare", dir.path("s.toml"), "--models", "pipe,thermal", "--out",
                          dir.path("cmp"), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string report = test::read_text(dir.path("cmp/report.md"));
  EXPECT_NE(report.find("exposed layer"), std::string::npos);
  EXPECT_NE(report.find("| granite (×0.1) |"), std::string::npos) << report;
  const std::string csv = test::read_text(dir.path("cmp/metrics.csv"));
  EXPECT_NE(csv.find("eroded_sand_m3,eroded_shale_m3,eroded_granite_m3"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir.path("cmp/pipe/geology.png")));
}

TEST(CliLayers, BadLayerInputIsRefusedWithOneLine) {
  ScratchDir dir;
  Heightmap big_rain(49, 49, 2.0, 2.0f);  // a rain fraction of 2
  write_terrain(dir.path("rain.npy"), big_rain);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"[[layers]]\nname = \"a\"\nthickness_file = \"missing.tif\"\n", "missing.tif"},
      {"[ground]\nrain_mask = \"rain.npy\"\n", "rain mask"},
      {"[ground]\nfrozen_mask = \"nope.npy\"\n", "nope.npy"},
      {"[[layers]]\nname = \"a\"\nthickness = 1\nfoo = 2\n", "layers[1].foo"},
  };
  for (const auto& [text, expected] : cases) {
    test::write_text(dir.path("bad.toml"), std::string(kTerrain) + text);
    const auto r = run_cli({"run", dir.path("bad.toml"), "--model", "pipe", "--steps", "1", "--out",
                            dir.path("out"), "--quiet"});
    EXPECT_EQ(r.exit_code, 2) << text;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path("out/metrics.json")));
  }
  // A rain mask shapes the whole terrain's rain: not with a disc.
  Heightmap half(49, 49, 2.0, 0.5f);
  write_terrain(dir.path("half.npy"), half);
  test::write_text(dir.path("disc.toml"),
                   std::string(kTerrain) +
                       "[ground]\nrain_mask = \"half.npy\"\n[rain]\nregion = "
                       "\"disc\"\ndisc_x = 40.0\ndisc_z = 40.0\ndisc_radius = 10.0\n");
  const auto d =
      run_cli({"run", dir.path("disc.toml"), "--steps", "1", "--out", dir.path("o2"), "--quiet"});
  EXPECT_EQ(d.exit_code, 2);
  EXPECT_NE(d.err.find("rain.region"), std::string::npos) << d.err;
  // An HDF5 output is for layered terrains only.
  const auto h = run_cli({"generate", "fbm", "--size", "17", "-o", dir.path("x.h5")});
  EXPECT_EQ(h.exit_code, 2);
  EXPECT_NE(h.err.find("layered"), std::string::npos) << h.err;
}

}  // namespace
}  // namespace runnel
