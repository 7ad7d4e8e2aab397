// SPDX-License-Identifier: MIT
// Terrain metrics on analytic cases (models.md): a cone's hypsometric integral is 1/3, a plane's
// slope, a hand-made drainage network's flow accumulation, a power-law surface's spectral slope.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <random>

#include "runnel/metrics/terrain_metrics.hpp"
#include "runnel/terrain/generators.hpp"

namespace runnel::metrics {
namespace {

TEST(TerrainMetrics, ConeHypsometricIntegralIsOneThird) {
  // The cone over its circular base: the vertices inside the base circle, as one row of samples.
  const int n = 801;
  const Heightmap cone = generate_terrain("cone", n, n, 1.0, 1, {{"relief", 0.5}, {"radius", 0.5}});
  const double c = (n - 1) / 2.0;
  std::vector<float> inside;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if (std::hypot(i - c, j - c) <= c) inside.push_back(cone.at(i, j));
    }
  }
  Heightmap samples(static_cast<int>(inside.size()), 1, 1.0);
  samples.h = inside;
  EXPECT_NEAR(hypsometric_integral(samples), 1.0 / 3.0, 2e-3);
  // A square pyramid over its square base: 1/3 as well.
  EXPECT_NEAR(hypsometric_integral(generate_terrain("pyramid", 401, 401, 1.0, 1, {{"base", 1.0}})),
              1.0 / 3.0, 5e-3);
}

TEST(TerrainMetrics, PlaneSlopeAndItsHistogram) {
  const Heightmap plane =
      generate_terrain("plane", 65, 65, 2.0, 1, {{"slope", 27.0}, {"azimuth", 40.0}});
  EXPECT_NEAR(mean_slope_degrees(plane), 27.0, 1e-4);
  const auto hist = slope_histogram(plane, 5.0);
  EXPECT_EQ(hist[5], 65 * 65) << "every vertex in the 25–30° bin";
  EXPECT_NEAR(erosion_score(plane), 0.0, 1e-6) << "a plane is perfectly regular";
}

TEST(TerrainMetrics, HandMadeDrainageNetwork) {
  // A valley floor along the middle row falling east, side slopes falling towards it: every vertex
  // of a column drains to the middle row, which drains east to the border.
  const int nx = 9, ny = 7;
  Heightmap t(nx, ny, 10.0);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i)
      t.at(i, j) = static_cast<float>(100 - 5 * i + 20 * std::abs(j - 3));
  }
  const auto area = flow_accumulation(t);
  const double cell_area = 100.0;
  // Interior side vertices drain only themselves...
  EXPECT_DOUBLE_EQ(area[1 * nx + 4], cell_area);
  EXPECT_DOUBLE_EQ(area[2 * nx + 4],
                   cell_area + cell_area);  // its uphill neighbour (row 1) flows through it
  // ...the valley vertex of column i gathers its own column's interior sides (rows 1, 2, 4, 5),
  // and everything upstream along the floor, which starts at column 1 (column 0 is the border).
  for (int i = 1; i < nx - 1; ++i)
    EXPECT_DOUBLE_EQ(area[3 * nx + i], cell_area * 5 * i) << "column " << i;
  // Channels (≥ 3 cells) are the floor vertices from column 1 on: seven D8 links of 10 m.
  EXPECT_NEAR(drainage_density(t, area, 3 * cell_area), 7 * 10.0 / (80.0 * 60.0), 1e-12);
}

TEST(TerrainMetrics, PowerLawSurfaceSpectralSlope) {
  // A synthetic surface with P(k) ∝ k^−β, β = 3 (random phases, deterministic seed): build it in
  // the Fourier domain and transform back with a plain inverse DFT of its few thousand modes.
  const int n = 128;
  const double beta = 3.0;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> phase(0, 2 * M_PI);
  Heightmap t(n, n, 1.0);
  std::vector<double> h(n * n, 0.0);
  for (int v = 0; v <= 40; ++v) {
    for (int u = -40; u <= 40; ++u) {
      if (v == 0 && u <= 0) continue;
      const double k = std::hypot(u, v) / n;
      if (k == 0 || std::hypot(u, v) > 40) continue;
      const double amplitude = std::pow(k, -beta / 2), p = phase(rng);
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i)
          h[j * n + i] += amplitude * std::cos(2 * M_PI * (u * i + v * j) / n + p);
      }
    }
  }
  for (int k = 0; k < n * n; ++k) t.h[k] = static_cast<float>(h[k]);
  EXPECT_NEAR(spectral_slope(t), -beta, 0.35);
}

TEST(TerrainMetrics, ErosionFollowingFlowCorrelatesWithDrainageArea) {
  const Heightmap before = generate_terrain("fbm", 65, 65, 1.0, 3, {{"relief", 0.2}});
  const auto area = flow_accumulation(before);
  Heightmap after = before;
  for (std::size_t k = 0; k < after.size(); ++k)
    after.h[k] -= static_cast<float>(1e-3 * std::log(area[k]));
  EXPECT_GT(erosion_flow_correlation(before, after), 0.9);
}

TEST(TerrainMetrics, StreamPowerCorrelationRanksErosionByDischargeAndSlope) {
  // Erosion that is a growing function of √A·S of the initial terrain ranks perfectly (ρ = 1);
  // erosion that shrinks with it, perfectly the other way.
  const Heightmap before = generate_terrain("fbm", 65, 65, 1.0, 5, {{"relief", 0.2}});
  const auto area = flow_accumulation(before);
  const auto slope = slope_degrees(before);
  Heightmap follows = before, opposes = before;
  for (std::size_t k = 0; k < before.size(); ++k) {
    const double index = std::sqrt(area[k]) * std::tan(slope[k] * M_PI / 180.0);
    follows.h[k] -= static_cast<float>(1e-3 * (1.0 + std::log1p(index)));
    opposes.h[k] -= static_cast<float>(1e-3 / (1.0 + index));
  }
  EXPECT_GT(stream_power_correlation(before, follows), 0.99);
  EXPECT_LT(stream_power_correlation(before, opposes), -0.99);
}

TEST(TerrainMetrics, DepressionsAndPeaksAreCountedOncePerBasinAndSummit) {
  Heightmap bowl(33, 33, 1.0);
  for (int j = 0; j < 33; ++j) {
    for (int i = 0; i < 33; ++i)
      bowl.at(i, j) = static_cast<float>((i - 16) * (i - 16) + (j - 11) * (j - 11));
  }
  EXPECT_EQ(closed_depressions(bowl), 1);
  EXPECT_EQ(local_peaks(bowl), 0);
  const Heightmap plane = generate_terrain("plane", 33, 33, 1.0, 1, {{"slope", 10.0}});
  EXPECT_EQ(closed_depressions(plane), 0);
  EXPECT_EQ(local_peaks(plane), 0);
  // Two pits dug into the plane and a spike raised on it.
  Heightmap rough = plane;
  rough.at(5, 5) -= 3.0f;
  rough.at(20, 9) -= 3.0f;
  rough.at(12, 25) += 3.0f;
  EXPECT_EQ(closed_depressions(rough), 2);
  EXPECT_EQ(local_peaks(rough), 1);
  EXPECT_EQ(local_peaks(generate_terrain("cone", 65, 65, 1.0, 1, {{"radius", 0.4}})), 1);
}

// The vertices strictly lower than all 8 neighbours, counted the plain way: where no two
// neighbouring vertices share a height, every closed depression has one such bottom.
long long strict_minima(const Heightmap& t) {
  long long count = 0;
  for (int j = 1; j + 1 < t.ny; ++j) {
    for (int i = 1; i + 1 < t.nx; ++i) {
      bool lowest = true;
      for (int dj = -1; dj <= 1; ++dj) {
        for (int di = -1; di <= 1; ++di)
          lowest &= (di == 0 && dj == 0) || t.at(i, j) < t.at(i + di, j + dj);
      }
      count += lowest;
    }
  }
  return count;
}

TEST(TerrainMetrics, FlatBottomedHollowsAndFlatTopsCountOnceAsOnDemsQuantisedToWholeMetres) {
  // Without ties, the count is the plain count of strict minima.
  const Heightmap hills = generate_terrain("fbm", 65, 65, 1.0, 3, {{"relief", 0.2}});
  EXPECT_GT(strict_minima(hills), 3);
  EXPECT_EQ(closed_depressions(hills), strict_minima(hills));
  // The flats of a DEM stored in whole metres, on a tilted plane: a hollow whose floor is level
  // over 3 × 3 vertices, a hill whose top is, a level shelf on the slope, a level hollow on the
  // border.
  Heightmap dem = generate_terrain("plane", 41, 41, 1.0, 1, {{"slope", 10.0}});
  for (int j = 0; j < 41; ++j) {
    for (int i = 0; i < 41; ++i) dem.at(i, j) += 0.07f * float(j);  // no two neighbours level
  }
  auto block = [&](int i0, int j0, float height) {
    for (int j = j0; j < j0 + 3; ++j) {
      for (int i = i0; i < i0 + 3; ++i) dem.at(i, j) = height;
    }
  };
  block(10, 10, dem.at(10, 10) - 5.0f);  // the hollow
  block(25, 25, dem.at(27, 27) + 5.0f);  // the hill
  block(10, 28, dem.at(11, 29));         // the shelf: higher ground on one side, lower on the other
  block(0, 20, dem.at(0, 20) - 5.0f);    // the hollow that opens onto the border
  EXPECT_EQ(strict_minima(dem), 0);      // the plain count sees no hollow at all
  EXPECT_EQ(closed_depressions(dem), 1);
  EXPECT_EQ(local_peaks(dem), 1);
  // The hollow's floor lowered by a few micrometres at one vertex: still one depression.
  dem.at(11, 11) -= 1e-5f;
  EXPECT_EQ(closed_depressions(dem), 1);
}

TEST(TerrainMetrics, ShortWavelengthShareSeparatesSpikesFromValleys) {
  // Δh a broad valley (a wavelength of 16 cells): almost nothing under 4 cells. Δh a checkerboard
  // (2 cells): almost everything.
  const Heightmap before(64, 64, 1.0);
  Heightmap valley = before, noise = before;
  for (int j = 0; j < 64; ++j) {
    for (int i = 0; i < 64; ++i) {
      valley.at(i, j) = static_cast<float>(std::sin(2 * M_PI * i / 16.0));
      noise.at(i, j) = ((i + j) % 2) ? 1.0f : -1.0f;
    }
  }
  EXPECT_LT(short_wavelength_share(before, valley), 0.02);
  EXPECT_GT(short_wavelength_share(before, noise), 0.98);
}

TEST(TerrainMetrics, ShortWavelengthPowerRatioTellsSmoothingFromRoughening) {
  // A tilted valley of 16 cells with a checkerboard of spikes on it. Removing the spikes (what a
  // talus relaxation does to a terrain too rough for its grid) puts all of Δh at short wavelengths,
  // so the Δh share reads it like roughening; the terrain's own short-wavelength power falls to
  // nothing. Doubling the spikes quadruples it.
  const int n = 64;
  Heightmap spiky(n, n, 1.0), smooth = spiky, rougher = spiky;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double valley = 0.3 * j + 4.0 * std::sin(2 * M_PI * i / 16.0);
      const double spike = ((i + j) % 2) ? 0.5 : -0.5;
      smooth.at(i, j) = static_cast<float>(valley);
      spiky.at(i, j) = static_cast<float>(valley + spike);
      rougher.at(i, j) = static_cast<float>(valley + 2 * spike);
    }
  }
  EXPECT_GT(short_wavelength_share(spiky, smooth), 0.98);
  EXPECT_LT(short_wavelength_power_ratio(spiky, smooth), 0.01);
  EXPECT_NEAR(short_wavelength_power_ratio(spiky, rougher), 4.0, 0.1);
  EXPECT_GT(short_wavelength_power_ratio(smooth, spiky), 100.0);
  EXPECT_DOUBLE_EQ(short_wavelength_power_ratio(spiky, spiky), 1.0);
  EXPECT_TRUE(std::isnan(short_wavelength_power_ratio(Heightmap(n, n, 1.0), spiky)))
      << "a flat initial terrain has no short-wavelength power to compare with";
}

}  // namespace
}  // namespace runnel::metrics
