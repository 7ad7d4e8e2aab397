// SPDX-License-Identifier: MIT
// The seeds' terrain synthesis against independent measures (docs/generators.md): the power
// spectrum's slope −(2H + 2), spectral terrains that tile without a seam, multifractals rougher
// high up than low down, RMP ridges on the Voronoi edges (found by brute force), the device equal
// to the host bit for bit, and no generator writing NaN or inf anywhere in its documented ranges.
#include <gtest/gtest.h>
#include <kissfft/kiss_fftnd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

#include "runnel/terrain/generator_util.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/noise_family.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

// The slope of log P(f) against log f, P the radially averaged power spectrum of the first n × n
// vertices (Hann-windowed, mean removed), fitted by least squares over f in [f0, f1] cycles/cell.
double spectral_slope(const Heightmap& t, int n, double f0, double f1) {
  std::vector<kiss_fft_cpx> in(static_cast<std::size_t>(n) * n), out(in.size());
  double mean = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) mean += t.at(i, j);
  mean /= double(n) * n;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double w =
          (0.5 - 0.5 * std::cos(2 * M_PI * i / n)) * (0.5 - 0.5 * std::cos(2 * M_PI * j / n));
      in[static_cast<std::size_t>(j) * n + i] = {static_cast<float>((t.at(i, j) - mean) * w), 0.0f};
    }
  const int dims[2] = {n, n};
  kiss_fftnd_cfg cfg = kiss_fftnd_alloc(dims, 2, 0, nullptr, nullptr);
  kiss_fftnd(cfg, in.data(), out.data());
  kiss_fft_free(cfg);
  std::vector<double> power(n / 2 + 1, 0.0), count(n / 2 + 1, 0.0);
  for (int v = 0; v < n; ++v)
    for (int u = 0; u < n; ++u) {
      const double fu = u <= n / 2 ? u : u - n, fv = v <= n / 2 ? v : v - n;
      const int bin = static_cast<int>(std::lround(std::hypot(fu, fv)));
      if (bin > n / 2) continue;
      const kiss_fft_cpx c = out[static_cast<std::size_t>(v) * n + u];
      power[bin] += double(c.r) * c.r + double(c.i) * c.i;
      count[bin] += 1;
    }
  double sx = 0, sy = 0, sxx = 0, sxy = 0, m = 0;
  for (int b = 1; b <= n / 2; ++b) {
    const double f = double(b) / n;
    if (f < f0 || f > f1 || count[b] == 0) continue;
    const double x = std::log(f), y = std::log(power[b] / count[b]);
    sx += x, sy += y, sxx += x * x, sxy += x * y, m += 1;
  }
  return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

TEST(Synthesis, SpectralTerrainsHaveThePowerLawOfTheirHurstExponent) {
  // Spectral synthesis draws every amplitude from the law itself: over 1/64 .. 1/8 cycles per
  // cell (a thousand modes a bin) the fitted slope of one terrain scatters by a few hundredths;
  // the window leaks a little power from low into high frequencies. ±0.15.
  for (double hurst : {0.4, 0.8, 1.2}) {
    const Heightmap t = generate_terrain("spectral", 257, 257, 1.0, 3, {{"hurst", hurst}});
    EXPECT_NEAR(spectral_slope(t, 256, 1.0 / 64, 1.0 / 8), -(2 * hurst + 2), 0.15) << "H " << hurst;
  }
}

TEST(Synthesis, FbmFollowsThePowerLawOfItsHurstExponentWithinAnOctavesRipple) {
  // fBm sums octaves of gradient noise, each band-limited around its frequency: the spectrum is the
  // power law −(2H + 2) modulated within each octave. Averaged over three octaves (1/64 .. 1/8) the
  // fit lands within ±0.4 of it, and it follows H: 0.4 steeper per 0.2 of H.
  std::vector<double> slopes;
  for (double hurst : {0.5, 0.7, 0.9}) {
    const Heightmap t = generate_terrain("fbm", 257, 257, 1.0, 3,
                                         {{"hurst", hurst}, {"octaves", 10}, {"frequency", 1.0}});
    slopes.push_back(spectral_slope(t, 256, 1.0 / 64, 1.0 / 8));
    EXPECT_NEAR(slopes.back(), -(2 * hurst + 2), 0.4) << "H " << hurst;
  }
  EXPECT_NEAR(slopes[0] - slopes[2], 0.8, 0.3) << "the slope follows H";
}

TEST(Synthesis, SpectralTerrainsTileInHeightAndSlope) {
  const Heightmap t = generate_terrain("spectral", 129, 97, 2.0, 9, {{"hurst", 0.7}});
  const int nx = t.nx, ny = t.ny;
  // Heights: the last column and row repeat the first.
  for (int j = 0; j < ny; ++j) EXPECT_EQ(t.at(0, j), t.at(nx - 1, j)) << j;
  for (int i = 0; i < nx; ++i) EXPECT_EQ(t.at(i, 0), t.at(i, ny - 1)) << i;
  // Slopes: across the seam of two copies side by side, the second difference
  // h(1) − 2h(0) + h(nx − 2) is no larger than inside the terrain (no kink); fBm's seam is a cliff.
  const auto seam_vs_interior = [](const Heightmap& h) {
    double seam = 0, interior = 0;
    for (int j = 0; j < h.ny; ++j) {
      seam = std::max(seam, double(std::fabs(h.at(1, j) - 2 * h.at(0, j) + h.at(h.nx - 2, j))));
      for (int i = 1; i < h.nx - 1; ++i)
        interior =
            std::max(interior, double(std::fabs(h.at(i + 1, j) - 2 * h.at(i, j) + h.at(i - 1, j))));
    }
    return seam / interior;
  };
  EXPECT_LE(seam_vs_interior(t), 1.0);
  const Heightmap f = generate_terrain("fbm", 129, 97, 2.0, 9);
  EXPECT_GT(std::fabs(f.at(0, 40) - f.at(nx - 1, 40)) + std::fabs(f.at(0, 70) - f.at(nx - 1, 70)),
            0.0f);
}

// RMS of the high-pass residual (h minus its 3 × 3 mean) of the vertices in a height band.
double roughness_in_band(const Heightmap& t, double lo_q, double hi_q) {
  std::vector<float> sorted = t.h;
  std::sort(sorted.begin(), sorted.end());
  const float lo = sorted[static_cast<std::size_t>(lo_q * (sorted.size() - 1))];
  const float hi = sorted[static_cast<std::size_t>(hi_q * (sorted.size() - 1))];
  double sum = 0;
  int count = 0;
  for (int j = 1; j < t.ny - 1; ++j)
    for (int i = 1; i < t.nx - 1; ++i) {
      const float h = t.at(i, j);
      if (h < lo || h > hi) continue;
      double mean = 0;
      for (int b = -1; b <= 1; ++b)
        for (int a = -1; a <= 1; ++a) mean += t.at(i + a, j + b);
      const double r = h - mean / 9;
      sum += r * r;
      ++count;
    }
  return std::sqrt(sum / count);
}

TEST(Synthesis, MultifractalsAreRougherHighUpThanLowDown) {
  // Musgrave's hybrid multifractal and heterogeneous terrain scale the detail by the height so
  // far: the highest third of the ground is rougher than the lowest third. Homogeneous fBm is the
  // control: there the two thirds are alike.
  for (const char* name : {"hybrid-multifractal", "hetero-terrain"}) {
    const Heightmap t = generate_terrain(name, 257, 257, 1.0, 4);
    const double ratio = roughness_in_band(t, 2.0 / 3, 1.0) / roughness_in_band(t, 0.0, 1.0 / 3);
    EXPECT_GT(ratio, 1.5) << name;
  }
  const Heightmap f = generate_terrain("fbm", 257, 257, 1.0, 4);
  const double control = roughness_in_band(f, 2.0 / 3, 1.0) / roughness_in_band(f, 0.0, 1.0 / 3);
  EXPECT_NEAR(control, 1.0, 0.3);
}

TEST(Synthesis, RmpRidgesLieOnTheVoronoiEdges) {
  // One level: every crest vertex (higher than both its neighbours along at least two of the four
  // grid directions: a line crossing a ridge) lies within a couple of cells of a Voronoi edge,
  // where the two nearest sites (by brute force over all sites) are as near: F2 − F1 ≤ 2·distance.
  GeneratorRequest r{129, 129, 1.0, 8, {}, nullptr};
  for (const GeneratorParam& p : find_generator("rmp-voronoi").params)
    r.values[p.key] = p.default_value;
  r.values["levels"] = 1;
  const Heightmap t = generate_terrain("rmp-voronoi", 129, 129, 1.0, 8, {{"levels", 1}});
  const auto sites = generator_util::rmp_voronoi_sites(r, 0);
  int crests = 0, on_edges = 0;
  for (int j = 1; j < t.ny - 1; ++j)
    for (int i = 1; i < t.nx - 1; ++i) {
      const float h = t.at(i, j);
      const int directions = int(h > t.at(i - 1, j) && h > t.at(i + 1, j)) +
                             int(h > t.at(i, j - 1) && h > t.at(i, j + 1)) +
                             int(h > t.at(i - 1, j - 1) && h > t.at(i + 1, j + 1)) +
                             int(h > t.at(i - 1, j + 1) && h > t.at(i + 1, j - 1));
      if (directions < 2) continue;
      double f1 = std::numeric_limits<double>::max(), f2 = f1;
      for (const auto& s : sites) {
        const double d = std::hypot(s.x - i, s.z - j);
        if (d < f1)
          f2 = f1, f1 = d;
        else if (d < f2)
          f2 = d;
      }
      ++crests;
      on_edges += f2 - f1 <= 2.0 * std::sqrt(2.0);  // within √2 cells of the edge
    }
  ASSERT_GT(crests, 200);
  EXPECT_EQ(on_edges, crests);
}

TEST(Synthesis, NoiseFamiliesGiveTheSameBytesOnTheDeviceAsOnTheHost) {
  for (const char* name : {"value-noise", "turbulence", "multifractal", "hybrid-multifractal",
                           "hetero-terrain", "varying-hurst"}) {
    const Heightmap host = generate_terrain(name, 97, 65, 1.5, 12);
    const Heightmap device = generate_terrain(name, 97, 65, 1.5, 12, {}, &test::compute());
    ASSERT_EQ(host.size(), device.size());
    EXPECT_EQ(0, std::memcmp(host.h.data(), device.h.data(), host.size() * sizeof(float))) << name;
  }
  NoiseFamily linear;
  linear.kind = NoiseFamily::kValue;
  linear.cosine = false;
  linear.by_height = false;
  EXPECT_EQ(noise_family_heights(linear, 40, 30, 1.0, nullptr),
            noise_family_heights(linear, 40, 30, 1.0, &test::compute()));
  NoiseFamily varying;
  varying.kind = NoiseFamily::kVaryingHurst;
  varying.by_height = true;
  EXPECT_EQ(noise_family_heights(varying, 40, 30, 1.0, nullptr),
            noise_family_heights(varying, 40, 30, 1.0, &test::compute()));
}

TEST(Synthesis, NoGeneratorWritesNanOrInfAnywhereInItsRanges) {
  // Every parameter at its lower and its upper bound, one at a time, the others at their defaults.
  for (const GeneratorSpec& g : generators()) {
    for (const GeneratorParam& p : g.params) {
      for (double v : {p.min_value, p.max_value}) {
        if (p.key == "count" && v > 1e4) v = 1e4;  // a million circles: slow, not different
        const Heightmap t = generate_terrain(g.name, 33, 25, 1.0, 7, {{p.key, v}});
        for (float h : t.h) ASSERT_TRUE(std::isfinite(h)) << g.name << " " << p.key << " = " << v;
      }
    }
  }
}

}  // namespace
}  // namespace runnel
