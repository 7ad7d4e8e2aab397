// SPDX-License-Identifier: MIT
// The layer stack's fixed part and its bookkeeping (docs/layers.md): [[layers]] read and refused as
// documented, each way of making a stratum against its geometry, the per-material accounting
// against a quantum-by-quantum count, and the device's ground_update against its C++ oracle.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "runnel/core/error.hpp"
#include "runnel/core/layers.hpp"
#include "runnel/ground/ground.hpp"
#include "runnel/ground/strata.hpp"
#include "runnel/sim/scenario.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/terrain_io.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

std::string error_of(const std::string& toml) {
  try {
    parse_scenario(toml, "s.toml");
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kUsage);
    return e.what();
  }
  return "no error";
}

std::vector<std::int64_t> fixed_of(const Heightmap& t, double q) {
  std::vector<std::int64_t> f(t.size());
  for (std::size_t k = 0; k < f.size(); ++k) f[k] = std::llround(t.h[k] / q);
  return f;
}

TEST(Layers, ScenarioLayersReadInOrderAndSurviveTheCheckpointText) {
  const Parameters p = parse_scenario(
      "[ground]\nbedrock_name = \"granite\"\n"
      "[[layers]]\nname = \"sand\"\nthickness = 2\nerodibility = 3\n"
      "[[layers]]\nname = \"shale\"\ndepth = 5\ndip = 10\nstrike = 30\n",
      "s.toml");
  ASSERT_EQ(p.layers().size(), 2u);
  EXPECT_EQ(layer_text(p.layers()[0], "name"), "sand");
  EXPECT_EQ(layer_shape(p.layers()[0]), LayerShape::kConstant);
  EXPECT_EQ(layer_shape(p.layers()[1]), LayerShape::kDipping);
  EXPECT_DOUBLE_EQ(layer_real(p.layers()[0], "erodibility"), 3.0);
  EXPECT_DOUBLE_EQ(layer_real(p.layers()[1], "erodibility"), 1.0);  // the default
  const Parameters back = parse_scenario(parameters_toml(p), "checkpoint");
  EXPECT_EQ(back.layers(), p.layers());
  EXPECT_EQ(back.text("ground.bedrock_name"), "granite");
}

TEST(Layers, BadLayersAreRefusedNamingTheLayerAndKey) {
  EXPECT_NE(error_of("[[layers]]\nname = \"a\"\nthickness = 1\ncolour = 3\n")
                .find("layers[1].colour: unknown layer key"),
            std::string::npos);
  EXPECT_NE(error_of("[[layers]]\nthickness = 1\n").find("layers[1].name"), std::string::npos);
  EXPECT_NE(error_of("[[layers]]\nname = \"a\"\nthickness = 1\n[[layers]]\nname = \"a\"\n"
                     "thickness = 1\n")
                .find("already defined"),
            std::string::npos);
  EXPECT_NE(error_of("[[layers]]\nname = \"a\"\nthickness = 1\ndepth = 3\n").find("exactly one"),
            std::string::npos);
  EXPECT_NE(error_of("[[layers]]\nname = \"a\"\n").find("exactly one"), std::string::npos);
  EXPECT_NE(error_of("[[layers]]\nname = \"bedrock\"\nthickness = 1\n").find("reserved"),
            std::string::npos);
  EXPECT_NE(error_of("[[layers]]\nname = \"a\"\nthickness = -1\n").find("layers[1].thickness"),
            std::string::npos);
  EXPECT_NE(error_of("[[layers]]\nname = \"a\"\nthickness = 1\ndip = 5\n").find("depth"),
            std::string::npos);
  EXPECT_NE(error_of("layers = 3\n").find("[[layers]]"), std::string::npos);
}

TEST(Strata, ConstantNoiseAndDippingContactsHaveTheirGeometry) {
  const double q = 1e-4;
  const Heightmap t = generate_terrain("fbm", 41, 33, 2.0, 3, {{"relief", 0.2}});
  const Parameters p = parse_scenario(
      "[[layers]]\nname = \"top\"\nthickness = 1.5\n"
      "[[layers]]\nname = \"wavy\"\nthickness = 2\nnoise_amplitude = 1\n"
      "[[layers]]\nname = \"tilted\"\ndepth = 20\ndip = 20\nstrike = 90\n",
      "s.toml");
  const Strata s = build_strata(p, t, fixed_of(t, q), q);
  ASSERT_EQ(s.strata, 3);
  ASSERT_EQ(s.materials.size(), 5u);
  EXPECT_EQ(s.materials[3].name, "bedrock");
  EXPECT_EQ(s.materials[4].name, "sediment");
  double wavy_min = 1e9, wavy_max = -1e9;
  const double slope = std::tan(20 * M_PI / 180);
  const double centre = t.at(t.nx / 2, t.ny / 2);
  for (int j = 0; j < t.ny; ++j) {
    for (int i = 0; i < t.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * t.nx + i;
      EXPECT_EQ(s.contact(0, k) - s.contact(1, k), 15000);  // 1.5 m
      const double wavy = double(s.contact(1, k) - s.contact(2, k)) * q;
      wavy_min = std::min(wavy_min, wavy);
      wavy_max = std::max(wavy_max, wavy);
      // Strike 90° (east): the contact dips to the south (+z) by tan(20°) per metre.
      const double plane = centre - 20.0 - slope * (j - t.ny / 2) * t.cell;
      const double expected = std::min(plane, double(s.contact(2, k)) * q);
      EXPECT_NEAR(double(s.contact(3, k)) * q, expected, 1.5 * q) << i << "," << j;
    }
  }
  EXPECT_GE(wavy_min, 1.0 - 1e-9);  // 2 ± 1 m
  EXPECT_LE(wavy_max, 3.0 + 1e-9);
  EXPECT_GT(wavy_max - wavy_min, 0.5) << "the noise varies the thickness";
}

TEST(Strata, ThicknessRasterIsResampledToTheTerrainWithAWarning) {
  test::ScratchDir dir;
  Heightmap raster(5, 5, 1.0);
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) raster.at(i, j) = static_cast<float>(i);  // 0..4 m west to east
  write_terrain(dir.path("thick.npy"), raster);
  const Heightmap t(9, 9, 1.0, 10.0f);
  const Parameters p = parse_scenario("[[layers]]\nname = \"a\"\nthickness_file = \"thick.npy\"\n",
                                      dir.path("s.toml"), dir.root().string());
  testing::internal::CaptureStderr();
  const Strata s = build_strata(p, t, fixed_of(t, 1e-3), 1e-3);
  EXPECT_NE(testing::internal::GetCapturedStderr().find("resampled"), std::string::npos);
  for (int i = 0; i < 9; ++i)  // vertex i of 9 lies at raster x = i/2: thickness i/2 m
    EXPECT_EQ(s.contact(0, i) - s.contact(1, i), 500 * i);
}

// Quantum by quantum: the rock between the initial surface and the rock surface now, each quantum
// booked to the band that holds it.
std::vector<std::int64_t> count_quanta(const Strata& s, const std::vector<std::int64_t>& rock) {
  std::vector<std::int64_t> eroded(s.strata + 1, 0);
  for (std::size_t k = 0; k < s.vertices(); ++k) {
    for (std::int64_t z = s.contact(0, k); z > rock[k]; --z) {  // the quantum (z − 1, z]
      int band = s.strata;
      for (int l = 0; l < s.strata; ++l)
        if (z <= s.contact(l, k) && z > s.contact(l + 1, k)) band = l;
      ++eroded[band];
    }
  }
  return eroded;
}

TEST(Strata, PerMaterialErosionMatchesAQuantumByQuantumCount) {
  Strata s;
  s.nx = 7;
  s.ny = 5;
  s.strata = 3;
  const std::size_t n = s.vertices();
  std::mt19937 rng(5);
  s.contacts.assign(4 * n, 0);
  std::vector<std::int64_t> rock(n);
  for (std::size_t k = 0; k < n; ++k) {
    s.contacts[k] = 200 + static_cast<std::int64_t>(rng() % 50);
    for (int l = 1; l <= 3; ++l)
      s.contacts[l * n + k] = s.contacts[(l - 1) * n + k] - static_cast<std::int64_t>(rng() % 30);
    rock[k] = s.contacts[k] - static_cast<std::int64_t>(rng() % 120);
  }
  EXPECT_EQ(eroded_per_material(s, rock), count_quanta(s, rock));
  for (std::size_t k = 0; k < n; ++k) {
    const int e = exposed_material(s, k, rock[k], 0);
    if (e < s.strata) {
      EXPECT_LE(rock[k], s.contact(e, k));
      EXPECT_GT(rock[k], s.contact(e + 1, k));
    } else {
      EXPECT_LE(rock[k], s.contact(s.strata, k));
    }
    EXPECT_EQ(exposed_material(s, k, rock[k], 1), s.sediment());
  }
}

TEST(Ground, DeviceUpdateBooksNetChangesAsTheOracleDoes) {
  ComputeContext& compute = test::compute();
  const double q = 1e-3;
  const Heightmap t = generate_terrain("fbm", 24, 20, 1.0, 9, {{"relief", 0.3}});
  Parameters p = parse_scenario(
      "[ground]\nsediment_erodibility = 5\nbedrock_erodibility = 0.25\n"
      "[[layers]]\nname = \"soft\"\nthickness = 0.05\nerodibility = 2\ntalus_angle = 30\n",
      "s.toml");
  p.set("erosion.height_quantum", q);
  DeviceTerrain terrain(compute, t, q);
  const auto h0 = terrain.download_fixed();
  Ground ground(compute, p, terrain, t, h0);
  std::vector<std::int64_t> h = h0, sediment(h.size(), 0);
  std::mt19937 rng(11);
  for (int step = 0; step < 6; ++step) {
    for (auto& v : h) v += static_cast<std::int64_t>(rng() % 81) - 50;  // mostly erosion
    terrain.upload_fixed(h);
    ground.update();
  }
  // The oracle, replayed: net change into the sediment first.
  std::mt19937 replay(11);
  std::vector<std::int64_t> hh = h0;
  for (int step = 0; step < 6; ++step) {
    for (std::size_t k = 0; k < hh.size(); ++k) {
      const std::int64_t d = static_cast<std::int64_t>(replay() % 81) - 50;
      hh[k] += d;
      sediment[k] = d > 0 ? sediment[k] + d : std::max<std::int64_t>(sediment[k] + d, 0);
    }
  }
  ASSERT_EQ(hh, h);
  EXPECT_EQ(ground.sediment(), sediment);
  const auto exposed = ground.exposed();
  int seen[3] = {0, 0, 0};
  for (std::size_t k = 0; k < h.size(); ++k) {
    const int e = exposed_material(ground.strata(), k, h[k] - sediment[k], sediment[k]);
    EXPECT_EQ(exposed[k], e) << k;
    ++seen[e];
  }
  for (int e = 0; e < 3; ++e) EXPECT_GT(seen[e], 0) << "material " << e << " never exposed";
  // The accounting identity holds exactly.
  const std::string report = ground.report().str();
  EXPECT_EQ(test::json_number(report, "layer_balance_quanta"), 0.0);
}

TEST(Ground, HardnessAndFrozenMasksScaleEveryMaterialsErodibility) {
  ComputeContext& compute = test::compute();
  test::ScratchDir dir;
  const Heightmap t = generate_terrain("fbm", 20, 16, 1.0, 2, {{"relief", 0.3}});
  Heightmap hardness(10, 8, 2.0, 0.5f), frozen(20, 16, 1.0, 0.0f);  // half the size: resampled
  for (int j = 0; j < 8; ++j) hardness.at(0, j) = 2.0f;
  frozen.at(19, 15) = 1.0f;
  write_terrain(dir.path("hard.npy"), hardness);
  write_terrain(dir.path("frozen.npy"), frozen);
  Parameters p = parse_scenario(
      "[ground]\nbedrock_erodibility = 0.4\nhardness_mask = \"hard.npy\"\n"
      "frozen_mask = \"frozen.npy\"\n",
      dir.path("s.toml"), dir.root().string());
  DeviceTerrain terrain(compute, t, 1e-4);
  testing::internal::CaptureStderr();
  Ground ground(compute, p, terrain, t, terrain.download_fixed());
  EXPECT_NE(testing::internal::GetCapturedStderr().find("ground.hardness_mask"), std::string::npos);
  std::vector<float> rock(t.size());
  compute.queue().enqueueReadBuffer(ground.bed().rock_erodibility, CL_TRUE, 0, rock.size() * 4,
                                    rock.data());
  EXPECT_FLOAT_EQ(rock[5 * 20 + 10], 0.4f * 0.5f);  // inside: hardness 0.5
  EXPECT_FLOAT_EQ(rock[3 * 20 + 0], 0.4f * 2.0f);   // the first column: hardness 2
  EXPECT_EQ(rock[15 * 20 + 19], 0.0f);              // frozen
}

}  // namespace
}  // namespace runnel
