// SPDX-License-Identifier: MIT
// Subdivision fractals on a 2^k + 1 grid, cropped to the request: midpoint displacement (Fournier
// et al. 1982, with Münch 2011's three-point edge rule as an option) and Voss's successive random
// additions (1985). docs/generators.md.
#include <vector>

#include "runnel/core/rng.hpp"
#include "runnel/terrain/generator_util.hpp"

namespace runnel::generator_util {
namespace {

// A square grid of 2^k + 1 vertices covering the request.
struct Lattice {
  int n = 1, size = 2;
  std::vector<double> h;
  explicit Lattice(const GeneratorRequest& r) {
    while (n + 1 < std::max(r.nx, r.ny)) n *= 2;
    size = n + 1;
    h.assign(static_cast<std::size_t>(size) * size, 0.0);
  }
  double& at(int i, int j) { return h[static_cast<std::size_t>(j) * size + i]; }
  Heightmap crop(const GeneratorRequest& r) {
    Heightmap t(r.nx, r.ny, r.cell);
    for (int j = 0; j < r.ny; ++j)
      for (int i = 0; i < r.nx; ++i) t.at(i, j) = static_cast<float>(at(i, j));
    return t;
  }
};

// Uniform in [−1, 1): one number per (stream, level, vertex).
double displacement(const GeneratorRequest& r, std::uint64_t stream, int level, int i, int j,
                    int size) {
  return 2.0 * rng_uniform_double(r.seed, stream + static_cast<std::uint64_t>(level),
                                  static_cast<std::uint64_t>(j) * size + i) -
         1.0;
}

}  // namespace

Heightmap midpoint(const GeneratorRequest& r) {
  constexpr std::uint64_t kStream = 0x4d4450ULL << 8;  // "MDP"
  Lattice g(r);
  const int n = g.n;
  for (int j : {0, n})
    for (int i : {0, n}) g.at(i, j) = displacement(r, kStream, 0, i, j, g.size);
  const double decay = std::pow(2.0, -r.values.at("roughness"));
  const bool three_points = r.values.at("edge_points") >= 3;
  double amplitude = 1.0;
  int level = 1;
  for (int step = n; step > 1; step /= 2, ++level) {
    const int half = step / 2;
    amplitude *= decay;
    for (int j = half; j < g.size; j += step)  // square centres: the mean of the four corners
      for (int i = half; i < g.size; i += step)
        g.at(i, j) = 0.25 * (g.at(i - half, j - half) + g.at(i + half, j - half) +
                             g.at(i - half, j + half) + g.at(i + half, j + half)) +
                     amplitude * displacement(r, kStream, level, i, j, g.size);
    // Edge midpoints: the mean of the edge's two end points (Fournier), or of the end points and
    // the centre of the squares beside the edge taken as a third point (Münch's three-point rule;
    // at the border there is one such square, inside the mean of the two).
    for (int j = 0; j < g.size; j += half) {
      for (int i = (j / half) % 2 == 0 ? half : 0; i < g.size; i += step) {
        const bool horizontal = (j / half) % 2 == 0;  // the edge runs along x
        const double a = horizontal ? g.at(i - half, j) : g.at(i, j - half);
        const double b = horizontal ? g.at(i + half, j) : g.at(i, j + half);
        double mean = 0.5 * (a + b);
        if (three_points) {
          double centres = 0;
          int count = 0;
          if (horizontal) {
            if (j >= half) centres += g.at(i, j - half), ++count;
            if (j + half < g.size) centres += g.at(i, j + half), ++count;
          } else {
            if (i >= half) centres += g.at(i - half, j), ++count;
            if (i + half < g.size) centres += g.at(i + half, j), ++count;
          }
          mean = (a + b + centres / count) / 3.0;
        }
        g.at(i, j) = mean + amplitude * displacement(r, kStream, level, i, j, g.size);
      }
    }
  }
  Heightmap t = g.crop(r);
  normalise(t, r.values.at("relief") * extent(r));
  return t;
}

Heightmap successive_additions(const GeneratorRequest& r) {
  // Each level interpolates the grid to twice the resolution (bilinearly) and then displaces every
  // point, old and new, by the level's amplitude.
  constexpr std::uint64_t kStream = 0x535241ULL << 8;  // "SRA"
  Lattice g(r);
  const double decay = std::pow(2.0, -r.values.at("roughness"));
  for (int j : {0, g.n})
    for (int i : {0, g.n}) g.at(i, j) = displacement(r, kStream, 0, i, j, g.size);
  double amplitude = 1.0;
  int level = 1;
  for (int step = g.n; step > 1; step /= 2, ++level) {
    const int half = step / 2;
    for (int j = 0; j < g.size; j += step)  // new points on the rows of the old ones
      for (int i = half; i < g.size; i += step)
        g.at(i, j) = 0.5 * (g.at(i - half, j) + g.at(i + half, j));
    for (int j = half; j < g.size; j += step)  // and the rows between
      for (int i = 0; i < g.size; i += half)
        g.at(i, j) = 0.5 * (g.at(i, j - half) + g.at(i, j + half));
    amplitude *= decay;
    for (int j = 0; j < g.size; j += half)
      for (int i = 0; i < g.size; i += half)
        g.at(i, j) += amplitude * displacement(r, kStream, level, i, j, g.size);
  }
  Heightmap t = g.crop(r);
  normalise(t, r.values.at("relief") * extent(r));
  return t;
}

}  // namespace runnel::generator_util
