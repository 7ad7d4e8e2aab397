// SPDX-License-Identifier: MIT
// Talus relaxation (cl/thermal.cl): converges to slopes no steeper than the talus angle and moves
// volume exactly; the height-aware variant keeps the peak higher.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>

#include "runnel/models/parameter_table.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/thermal.hpp"
#include "runnel/terrain/thermal_reference.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

// The steepest slope (degrees) between 4-neighbours.
double steepest(const Heightmap& t) {
  double s = 0;
  for (int j = 0; j < t.ny; ++j) {
    for (int i = 0; i < t.nx; ++i) {
      if (i + 1 < t.nx) s = std::max(s, std::fabs(double(t.at(i + 1, j)) - t.at(i, j)));
      if (j + 1 < t.ny) s = std::max(s, std::fabs(double(t.at(i, j + 1)) - t.at(i, j)));
    }
  }
  return std::atan(s / t.cell) * 180.0 / M_PI;
}

TEST(Thermal, ConvergesToTheTalusAngleAndConservesVolume) {
  // A 60° pyramid relaxes towards 35°.
  const Heightmap pyramid =
      generate_terrain("pyramid", 41, 41, 1.0, 1, {{"relief", 0.8}, {"base", 0.5}});
  ASSERT_GT(steepest(pyramid), 55.0);
  DeviceTerrain terrain(compute(), pyramid);
  const auto before = terrain.download_fixed();
  ThermalSettings s = ThermalSettings::from(default_parameters());
  s.talus_angle_deg = 35.0;
  ThermalRelaxation thermal(compute(), terrain, s);
  for (int k = 0; k < 600; ++k) thermal.relax();
  const auto after = terrain.download_fixed();
  EXPECT_EQ(std::accumulate(before.begin(), before.end(), 0LL),
            std::accumulate(after.begin(), after.end(), 0LL))
      << "volume is moved in whole quanta, never made or lost";
  EXPECT_LT(steepest(terrain.download()), 35.0 + 1.0)
      << "no slope steeper than the talus angle (within 1°)";
}

TEST(Thermal, HeightAwareVariantKeepsPeaksSharper) {
  const Heightmap cone =
      generate_terrain("cone", 41, 41, 1.0, 1, {{"relief", 0.8}, {"radius", 0.3}});
  double peaks[2];
  for (int variant = 0; variant < 2; ++variant) {
    DeviceTerrain terrain(compute(), cone);
    ThermalSettings s = ThermalSettings::from(default_parameters());
    s.talus_angle_deg = 30.0;
    s.height_aware = variant == 1;
    s.hardness = 1.0;
    ThermalRelaxation thermal(compute(), terrain, s);
    for (int k = 0; k < 300; ++k) thermal.relax();
    peaks[variant] = terrain.download().max_height();
  }
  EXPECT_GT(peaks[1], peaks[0] + 1.0);
}

}  // namespace
}  // namespace runnel

namespace runnel {
namespace {

// One pass on a random rough terrain against the plain C++ oracle (thermal_reference), plain and
// height-aware.
TEST(Thermal, OnePassMatchesThePlainCppReference) {
  const int nx = 23, ny = 19;
  const double quantum = 1e-6, cell = 0.5;
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<std::int64_t> relief(0, 2'000'000);  // 0–2 m: steep at 0.5 m cells
  Heightmap rough(nx, ny, cell);
  for (float& h : rough.h) h = static_cast<float>(relief(rng) * quantum);
  for (bool height_aware : {false, true}) {
    DeviceTerrain terrain(compute(), rough, quantum);
    const std::vector<std::int64_t> before = terrain.download_fixed();
    ThermalSettings s = ThermalSettings::from(default_parameters());
    s.talus_angle_deg = 30.0;
    s.rate = 0.37;
    s.height_aware = height_aware;
    s.hardness = 0.8;
    ThermalRelaxation(compute(), terrain, s).relax();
    const std::int64_t talus =
        std::llround(cell * std::tan(s.talus_angle_deg * M_PI / 180.0) / quantum);
    const auto reference =
        thermal_reference::relax(before, nx, ny, talus, s.rate, s.height_aware, s.hardness);
    const auto c = test::compare_quanta(terrain.download_fixed(), reference, before);
    EXPECT_GT(c.changed, nx * ny / 2) << "the case relaxes most vertices";
    EXPECT_LE(c.worst, 8) << "at most a quantum per outflow and inflow apart (float vs double)";
    EXPECT_GT(c.exact_share, 0.9);
  }
}

}  // namespace
}  // namespace runnel
