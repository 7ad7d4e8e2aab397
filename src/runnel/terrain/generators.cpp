// SPDX-License-Identifier: MIT
// Terrain generators. Fractal terrains are scaled to heights in [0, relief·extent]; shapes are
// defined by angles and fractions of the horizontal extent, so any size and cell size make sense.
// docs/generators.md gives each definition.
#include "runnel/terrain/generators.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "runnel/core/error.hpp"
#include "runnel/core/rng.hpp"
#include "runnel/core/text.hpp"
#include "runnel/terrain/generator_util.hpp"
#include "runnel/terrain/noise.hpp"

namespace runnel {

void generator_util::normalise(Heightmap& t, double relief_m) {
  const double lo = t.min_height(), hi = t.max_height();
  const double scale = hi > lo ? relief_m / (hi - lo) : 0.0;
  for (float& v : t.h) v = static_cast<float>((v - lo) * scale);
}

namespace {

using namespace generator_util;

// Tilts a terrain so it falls towards the east (+x) at `degrees`: water then drains off that edge.
void add_tilt(Heightmap& t, double degrees) {
  if (degrees == 0.0) return;
  const double slope = std::tan(degrees * kDeg), width = (t.nx - 1) * t.cell;
  for (int j = 0; j < t.ny; ++j) {
    for (int i = 0; i < t.nx; ++i) t.at(i, j) += static_cast<float>(slope * (width - i * t.cell));
  }
}

Heightmap diamond_square(const GeneratorRequest& r) {
  int n = 1;
  while (n + 1 < std::max(r.nx, r.ny)) n *= 2;
  const int size = n + 1;  // the algorithm needs 2^k + 1; crop afterwards
  std::vector<double> h(static_cast<std::size_t>(size) * size, 0.0);
  auto at = [&](int i, int j) -> double& { return h[static_cast<std::size_t>(j) * size + i]; };
  auto noise = [&](int level, int i, int j) {
    return 2.0 * rng_uniform_double(r.seed, 0x4453ULL + level,
                                    static_cast<std::uint64_t>(j) * size + i) -
           1.0;
  };
  at(0, 0) = noise(0, 0, 0);
  at(n, 0) = noise(0, n, 0);
  at(0, n) = noise(0, 0, n);
  at(n, n) = noise(0, n, n);
  const double decay = std::pow(2.0, -r.values.at("roughness"));
  double amplitude = 1.0;
  int level = 1;
  for (int step = n; step > 1; step /= 2, ++level) {
    const int half = step / 2;
    amplitude *= decay;
    for (int j = half; j < size; j += step) {  // diamond: centres of squares
      for (int i = half; i < size; i += step) {
        at(i, j) = 0.25 * (at(i - half, j - half) + at(i + half, j - half) +
                           at(i - half, j + half) + at(i + half, j + half)) +
                   amplitude * noise(level, i, j);
      }
    }
    for (int j = 0; j < size;
         j += half) {  // square: edge midpoints, averaging the neighbours that exist
      for (int i = (j / half) % 2 == 0 ? half : 0; i < size; i += step) {
        double sum = 0.0;
        int count = 0;
        if (i >= half) {
          sum += at(i - half, j);
          ++count;
        }
        if (i + half < size) {
          sum += at(i + half, j);
          ++count;
        }
        if (j >= half) {
          sum += at(i, j - half);
          ++count;
        }
        if (j + half < size) {
          sum += at(i, j + half);
          ++count;
        }
        at(i, j) = sum / count + amplitude * noise(level, i, j);
      }
    }
  }
  Heightmap t(r.nx, r.ny, r.cell);
  for (int j = 0; j < r.ny; ++j) {
    for (int i = 0; i < r.nx; ++i) t.at(i, j) = static_cast<float>(at(i, j));
  }
  normalise(t, r.values.at("relief") * extent(r));
  return t;
}

Heightmap fault(const GeneratorRequest& r) {
  // Fault formation: each random line raises one side; the displacement shrinks with every cut.
  Heightmap t(r.nx, r.ny, r.cell);
  const int cuts = static_cast<int>(r.values.at("cuts"));
  std::vector<double> acc(t.size(), 0.0);
  for (int c = 0; c < cuts; ++c) {
    const double angle = 2.0 * M_PI * rng_uniform_double(r.seed, 0x4641ULL, 3 * c);
    const double px = rng_uniform_double(r.seed, 0x4641ULL, 3 * c + 1) * (r.nx - 1);
    const double pz = rng_uniform_double(r.seed, 0x4641ULL, 3 * c + 2) * (r.ny - 1);
    const double nxd = std::cos(angle), nzd = std::sin(angle);
    const double displacement = 1.0 - 0.9 * c / std::max(1, cuts);
    for (int j = 0; j < r.ny; ++j) {
      for (int i = 0; i < r.nx; ++i) {
        if ((i - px) * nxd + (j - pz) * nzd > 0)
          acc[static_cast<std::size_t>(j) * r.nx + i] += displacement;
      }
    }
  }
  // Box smoothing passes soften the cliffs the cuts leave.
  const int passes = static_cast<int>(r.values.at("smoothing"));
  for (int p = 0; p < passes; ++p) {
    std::vector<double> next(acc.size());
    for (int j = 0; j < r.ny; ++j) {
      for (int i = 0; i < r.nx; ++i) {
        double sum = 0.0;
        int count = 0;
        for (int dj = -1; dj <= 1; ++dj) {
          for (int di = -1; di <= 1; ++di) {
            const int a = i + di, b = j + dj;
            if (a < 0 || b < 0 || a >= r.nx || b >= r.ny) continue;
            sum += acc[static_cast<std::size_t>(b) * r.nx + a];
            ++count;
          }
        }
        next[static_cast<std::size_t>(j) * r.nx + i] = sum / count;
      }
    }
    acc.swap(next);
  }
  for (std::size_t k = 0; k < acc.size(); ++k) t.h[k] = static_cast<float>(acc[k]);
  normalise(t, r.values.at("relief") * extent(r));
  return t;
}

Heightmap fbm(const GeneratorRequest& r) {
  const double hurst = r.values.at("hurst"), lacunarity = r.values.at("lacunarity");
  const int octaves = static_cast<int>(r.values.at("octaves"));
  const double base = r.values.at("frequency") / extent(r);  // cycles per metre
  Heightmap t = from_function(r, [&](double x, double z) {
    double sum = 0.0, freq = base, amp = 1.0;
    for (int o = 0; o < octaves; ++o) {
      sum += amp * gradient_noise(x * freq, z * freq, r.seed, o);
      freq *= lacunarity;
      amp *= std::pow(lacunarity, -hurst);
    }
    return sum;
  });
  normalise(t, r.values.at("relief") * extent(r));
  add_tilt(t, r.values.at("tilt"));
  return t;
}

Heightmap ridged(const GeneratorRequest& r) {
  // Musgrave's ridged multifractal: sharp crests from 1 − |noise|, each octave weighted by the
  // last.
  const double hurst = r.values.at("hurst"), lacunarity = r.values.at("lacunarity");
  const double offset = r.values.at("offset"), gain = r.values.at("gain");
  const int octaves = static_cast<int>(r.values.at("octaves"));
  const double base = r.values.at("frequency") / extent(r);
  Heightmap t = from_function(r, [&](double x, double z) {
    double freq = base;
    double signal = offset - std::fabs(gradient_noise(x * freq, z * freq, r.seed, 0));
    signal *= signal;
    double sum = signal;
    for (int o = 1; o < octaves; ++o) {
      freq *= lacunarity;
      const double weight = std::clamp(signal * gain, 0.0, 1.0);
      signal = offset - std::fabs(gradient_noise(x * freq, z * freq, r.seed, o));
      signal = signal * signal * weight;
      sum += signal * std::pow(lacunarity, -hurst * o);
    }
    return sum;
  });
  normalise(t, r.values.at("relief") * extent(r));
  return t;
}

Heightmap crooked(const GeneratorRequest& r) {
  // Fritz 2016's "crooked surface": an inclined plane bent by crossing sine waves.
  const double L = extent(r), slope = std::tan(r.values.at("slope") * kDeg);
  const double amp = r.values.at("amplitude") * L, waves = r.values.at("waves");
  return from_function(r, [&](double x, double z) {
    const double u = x / L, v = z / L;
    return slope * (L - x) + amp * (1.0 + std::sin(2 * M_PI * waves * u) *
                                              std::cos(2 * M_PI * waves * v * 0.75 + 0.5));
  });
}

Heightmap pyramid(const GeneratorRequest& r) {
  const double L = extent(r), half = 0.5 * r.values.at("base") * L,
               height = r.values.at("relief") * L;
  const double cx = 0.5 * (r.nx - 1) * r.cell, cz = 0.5 * (r.ny - 1) * r.cell;
  return from_function(r, [&](double x, double z) {
    return height * std::max(0.0, 1.0 - std::max(std::fabs(x - cx), std::fabs(z - cz)) / half);
  });
}

Heightmap hemisphere(const GeneratorRequest& r) {
  const double R = r.values.at("radius") * extent(r);
  const double cx = 0.5 * (r.nx - 1) * r.cell, cz = 0.5 * (r.ny - 1) * r.cell;
  return from_function(r, [&](double x, double z) {
    const double d2 = (x - cx) * (x - cx) + (z - cz) * (z - cz);
    return d2 < R * R ? std::sqrt(R * R - d2) : 0.0;
  });
}

Heightmap plane(const GeneratorRequest& r) {
  const double slope = std::tan(r.values.at("slope") * kDeg), az = r.values.at("azimuth") * kDeg;
  const double ux = std::cos(az), uz = std::sin(az);
  const double lx = (r.nx - 1) * r.cell, lz = (r.ny - 1) * r.cell;
  const double lowest = std::min(0.0, lx * ux) + std::min(0.0, lz * uz);  // keep heights ≥ 0
  return from_function(r, [&](double x, double z) { return slope * (x * ux + z * uz - lowest); });
}

Heightmap cone(const GeneratorRequest& r) {
  const double L = extent(r), R = r.values.at("radius") * L, height = r.values.at("relief") * L;
  const double cx = 0.5 * (r.nx - 1) * r.cell, cz = 0.5 * (r.ny - 1) * r.cell;
  return from_function(r, [&](double x, double z) {
    return height * std::max(0.0, 1.0 - std::hypot(x - cx, z - cz) / R);
  });
}

Heightmap v_valley(const GeneratorRequest& r) {
  // A valley whose axis runs north to south along the middle column, falling towards the south.
  const double side = std::tan(r.values.at("side_slope") * kDeg),
               axis = std::tan(r.values.at("axis_slope") * kDeg);
  const double cx = 0.5 * (r.nx - 1) * r.cell, lz = (r.ny - 1) * r.cell;
  return from_function(
      r, [&](double x, double z) { return side * std::fabs(x - cx) + axis * (lz - z); });
}

}  // namespace

const std::vector<GeneratorSpec>& generators() {
  // The shared parameters here, not at namespace scope: generators() may run during another
  // file's static initialisation (a test's parameter list), before namespace-scope objects exist.
  const GeneratorParam kRelief{
      "relief", 0.25, "fraction of extent", "height range as a fraction of the horizontal extent",
      0.0,      10.0};
  const GeneratorParam kHurst{
      "hurst", 0.8, "1", "Hurst exponent H: amplitude falls as lacunarity^(-H) per octave",
      0.0,     2.0};
  const GeneratorParam kLacunarity{"lacunarity", 2.0, "1", "frequency ratio between octaves",
                                   1.01,         8.0};
  const GeneratorParam kOctaves{"octaves", 8, "1", "number of noise octaves", 1, 24, true};
  const GeneratorParam kFrequency{
      "frequency", 2.0, "cycles per extent", "frequency of the first octave", 0.01, 1000.0};
  static const std::vector<GeneratorSpec> specs = {
      {"diamond-square",
       "midpoint displacement fractal (Fournier 1982)",
       {kRelief, {"roughness", 0.8, "1", "amplitude falls by 2^(-roughness) per level", 0.0, 3.0}},
       diamond_square},
      {"fault",
       "fault formation: random cut lines raise one side",
       {kRelief,
        {"cuts", 200, "1", "number of fault lines", 1, 100000, true},
        {"smoothing", 2, "1", "3x3 smoothing passes after faulting", 0, 1000, true}},
       fault},
      {"fbm",
       "fractional Brownian motion from gradient noise",
       {kRelief,
        kHurst,
        kLacunarity,
        kOctaves,
        kFrequency,
        {"tilt", 0.0, "deg", "overall slope falling east (+x), so water drains off the east edge",
         -60.0, 60.0}},
       fbm},
      {"ridged",
       "ridged multifractal (Musgrave 1994)",
       {kRelief,
        kHurst,
        kLacunarity,
        kOctaves,
        kFrequency,
        {"offset", 1.0, "1", "ridge offset", 0.0, 4.0},
        {"gain", 2.0, "1", "weighting gain between octaves", 0.0, 10.0}},
       ridged},
      {"crooked",
       "inclined plane bent by crossing sine waves (Fritz 2016's crooked surface)",
       {{"slope", 20.0, "deg", "mean slope, falling towards east", 0.0, 80.0},
        {"amplitude", 0.05, "fraction of extent", "wave amplitude", 0.0, 1.0},
        {"waves", 2.0, "1", "waves across the extent", 0.0, 100.0}},
       crooked},
      {"pyramid",
       "square pyramid in the centre",
       {{"relief", 0.3, "fraction of extent", "apex height", 0.0, 10.0},
        {"base", 0.8, "fraction of extent", "base width", 0.01, 1.0}},
       pyramid},
      {"hemisphere",
       "hemisphere in the centre",
       {{"radius", 0.4, "fraction of extent", "radius (and height)", 0.01, 0.5}},
       hemisphere},
      {"plane",
       "inclined plane",
       {{"slope", 15.0, "deg", "inclination", 0.0, 85.0},
        {"azimuth", 0.0, "deg", "direction of rise: 0 = east (+x), 90 = south (+z)", -360.0,
         360.0}},
       plane},
      {"cone",
       "cone in the centre",
       {{"relief", 0.3, "fraction of extent", "apex height", 0.0, 10.0},
        {"radius", 0.45, "fraction of extent", "base radius", 0.01, 1.0}},
       cone},
      {"v-valley",
       "V-shaped valley along the middle column, falling south",
       {{"side_slope", 20.0, "deg", "slope of the valley sides", 0.0, 80.0},
        {"axis_slope", 5.0, "deg", "slope along the valley axis", 0.0, 80.0}},
       v_valley},
      // The seeds' synthesis (docs/generators.md).
      {"midpoint",
       "midpoint displacement of squares (Fournier 1982), Münch 2011's three-point edge rule",
       {kRelief,
        {"roughness", 0.8, "1", "amplitude falls by 2^(-roughness) per level", 0.0, 3.0},
        {"edge_points", 3, "1",
         "edge midpoints from 2 points (the edge's ends) or 3 (and the centre beside it)", 2, 3}},
       midpoint},
      {"successive-additions",
       "successive random additions (Voss 1985): refine, then displace every point",
       {kRelief, {"roughness", 0.8, "1", "amplitude falls by 2^(-roughness) per level", 0.0, 3.0}},
       successive_additions},
      {"value-noise",
       "octave value noise, linear or cosine interpolation (Münch 2011's \"Perlin noise\"; on the "
       "device)",
       {kRelief,
        {"frequency", 4.0, "cycles per extent", "frequency of the first octave", 0.01, 1000.0},
        {"octaves", 6, "1", "number of octaves", 1, 24},
        {"persistence", 0.5, "1", "amplitude ratio between octaves", 0.0, 1.0},
        kLacunarity,
        {"interpolation", 1, "1", "0: linear, 1: cosine", 0, 1}},
       value_noise_terrain,
       true},
      {"turbulence",
       "Perlin turbulence: fBm of |gradient noise| (creased valleys; on the device)",
       {kRelief, kHurst, kLacunarity, kOctaves, kFrequency},
       turbulence,
       true},
      {"multifractal",
       "Musgrave's multiplicative multifractal (on the device)",
       {kRelief,
        {"hurst", 0.7, "1", "Hurst exponent H", 0.0, 2.0},
        kLacunarity,
        {"octaves", 6, "1", "number of noise octaves", 1, 24},
        kFrequency,
        {"offset", 1.0, "1",
         "added to the noise before multiplying (keeps the factors positive above 0.7)", 0.0, 4.0}},
       multifractal,
       true},
      {"hybrid-multifractal",
       "Musgrave's hybrid multifractal: smooth valleys, rough peaks (on the device)",
       {kRelief,
        {"hurst", 0.25, "1", "Hurst exponent H", 0.0, 2.0},
        kLacunarity,
        kOctaves,
        kFrequency,
        {"offset", 0.7, "1", "added to the noise of every octave", 0.0, 4.0}},
       hybrid_multifractal,
       true},
      {"hetero-terrain",
       "Musgrave's heterogeneous terrain: each octave scaled by the height so far (on the device)",
       {kRelief,
        {"hurst", 0.7, "1", "Hurst exponent H", 0.0, 2.0},
        kLacunarity,
        {"octaves", 6, "1", "number of noise octaves", 1, 24},
        kFrequency,
        {"offset", 0.8, "1", "added to the noise of every octave", 0.0, 4.0}},
       hetero_terrain,
       true},
      {"varying-hurst",
       "fBm whose Hurst exponent varies with position or height (Jourdan 2008; on the device)",
       {kRelief,
        {"hurst", 0.9, "1", "H at x = 0 (by position) or at the lowest ground (by height)", 0.0,
         2.0},
        {"hurst_end", 0.3, "1",
         "H at the east edge (by position) or on the highest ground (by height)", 0.0, 2.0},
        {"by_height", 0, "1",
         "0: H varies from west to east; 1: with the height of the first two octaves", 0, 1},
        kLacunarity,
        kOctaves,
        kFrequency},
       varying_hurst,
       true},
      {"spectral",
       "spectral synthesis by inverse FFT, power ∝ f^-(2H+2), tileable in height and slope",
       {kRelief,
        kHurst,
        {"min_wavelength", 2.0, "cells",
         "shortest wavelength kept (2: all up to the grid's Nyquist)", 2.0, 1e6}},
       spectral},
      {"circles",
       "random hemisphere bumps added up (Münch 2011's circle algorithm)",
       {kRelief,
        {"count", 200, "1", "number of circles", 1, 1e6},
        {"radius_min", 0.02, "fraction of extent", "smallest radius", 0.001, 1.0},
        {"radius_max", 0.1, "fraction of extent", "largest radius", 0.001, 1.0}},
       circles},
      {"rmp-voronoi",
       "repeated magnification and probing, Voronoi form: ridges on the Voronoi edges (Kamal & "
       "Uddin; Fritz 2016)",
       {kRelief,
        {"cells", 4.0, "sites per extent", "Voronoi sites across the extent at the first level",
         0.5, 256.0},
        {"levels", 3, "1", "magnifications (each doubles the sites per extent)", 1, 8},
        {"gain", 0.5, "1", "height ratio between levels", 0.0, 1.0},
        {"width", 0.5, "site spacings", "half-width of a ridge at its foot", 0.01, 4.0}},
       rmp_voronoi},
      {"rmp-graph",
       "repeated magnification and probing, graph form: a spanning tree of peaks, refined (Kamal & "
       "Uddin; Fritz 2016)",
       {kRelief,
        {"peaks", 24, "1", "peaks joined by their minimum spanning tree", 2, 1000},
        {"levels", 4, "1", "magnifications (each splits every ridge segment)", 0, 10},
        {"wander", 0.25, "1", "sideways probe of a split, times the segment's length", 0.0, 1.0},
        {"flank", 3.0, "m/m",
         "slope of the flanks falling from the ridges (before the relief is scaled)", 0.01, 100.0}},
       rmp_graph},
  };
  return specs;
}

const GeneratorSpec& find_generator(const std::string& name) {
  std::string names;
  for (auto& g : generators()) {
    if (g.name == name) return g;
    names += (names.empty() ? "" : ", ") + g.name;
  }
  throw input_error("generator '" + name + "': unknown (choose one of " + names + ")");
}

Heightmap generate_terrain(const std::string& name, int nx, int ny, double cell, std::uint64_t seed,
                           const std::map<std::string, double>& overrides,
                           ComputeContext* compute) {
  const GeneratorSpec& spec = find_generator(name);
  if (nx < 2 || ny < 2 || nx > kMaxSide || ny > kMaxSide ||
      static_cast<long long>(nx) * ny > kMaxVertices) {
    throw input_error("--size: " + std::to_string(nx) + " x " + std::to_string(ny) +
                      " is outside 2.." + std::to_string(kMaxSide) + " per side");
  }
  if (!(cell > 0.0) || !std::isfinite(cell))
    throw input_error("--cell: must be a positive number of metres");
  GeneratorRequest request{nx, ny, cell, seed, {}, compute};
  for (auto& p : spec.params) request.values[p.key] = p.default_value;
  for (const auto& entry : overrides) {
    const std::string& key = entry.first;  // not a structured binding: lambdas capture it
    const double value = entry.second;
    auto it =
        std::find_if(spec.params.begin(), spec.params.end(), [&](auto& p) { return p.key == key; });
    if (it == spec.params.end()) {
      std::string keys;
      for (auto& p : spec.params) keys += (keys.empty() ? "" : ", ") + p.key;
      throw input_error("--set " + key + ": not a parameter of generator '" + name +
                        "' (known: " + keys + ")");
    }
    if (!std::isfinite(value) || value < it->min_value || value > it->max_value) {
      std::ostringstream msg;
      msg << "--set " << key << "=" << value << ": outside the valid range [" << it->min_value
          << ", " << it->max_value << "] " << it->unit;
      throw input_error(msg.str());
    }
    if (it->whole && value != std::floor(value))
      throw input_error("--set " + key + "=" + format_number(value) + ": a count, a whole number");
    request.values[key] = value;
  }
  return spec.make(request);
}

}  // namespace runnel
