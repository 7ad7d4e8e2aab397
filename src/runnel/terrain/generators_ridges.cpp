// SPDX-License-Identifier: MIT
// Shapes placed at random: Münch 2011's circles (hemisphere bumps), and Kamal & Uddin's repeated
// magnification and probing (RMP, as Fritz 2016 uses it) in its Voronoi and its graph form.
// docs/generators.md.
#include <limits>
#include <utility>
#include <vector>

#include "runnel/core/rng.hpp"
#include "runnel/terrain/generator_util.hpp"

namespace runnel::generator_util {
namespace {

double uniform(const GeneratorRequest& r, std::uint64_t stream, std::uint64_t counter) {
  return rng_uniform_double(r.seed, stream, counter);
}

}  // namespace

Heightmap circles(const GeneratorRequest& r) {
  constexpr std::uint64_t kStream = 0x434952ULL << 8;  // "CIR"
  const double L = extent(r);
  const double rmin = r.values.at("radius_min") * L,
               rmax = std::max(rmin, r.values.at("radius_max") * L);
  const int count = static_cast<int>(r.values.at("count"));
  std::vector<double> h(static_cast<std::size_t>(r.nx) * r.ny, 0.0);
  for (int c = 0; c < count; ++c) {
    const double cx = uniform(r, kStream, 3 * c) * (r.nx - 1) * r.cell;
    const double cz = uniform(r, kStream, 3 * c + 1) * (r.ny - 1) * r.cell;
    const double R = rmin + (rmax - rmin) * uniform(r, kStream, 3 * c + 2);
    const int i0 = std::max(0, static_cast<int>(std::floor((cx - R) / r.cell)));
    const int i1 = std::min(r.nx - 1, static_cast<int>(std::ceil((cx + R) / r.cell)));
    const int j0 = std::max(0, static_cast<int>(std::floor((cz - R) / r.cell)));
    const int j1 = std::min(r.ny - 1, static_cast<int>(std::ceil((cz + R) / r.cell)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const double dx = i * r.cell - cx, dz = j * r.cell - cz, d2 = dx * dx + dz * dz;
        if (d2 < R * R) h[static_cast<std::size_t>(j) * r.nx + i] += std::sqrt(R * R - d2);
      }
  }
  Heightmap t(r.nx, r.ny, r.cell);
  for (std::size_t k = 0; k < h.size(); ++k) t.h[k] = static_cast<float>(h[k]);
  normalise(t, r.values.at("relief") * L);
  return t;
}

namespace {

// The jittered grid of magnification `level`: cells `spacing` metres wide, a = −1..gx, b = −1..gz.
struct SiteGrid {
  double spacing;
  int gx, gz;
  int row() const { return gx + 2; }
};

SiteGrid site_grid(const GeneratorRequest& r, int level) {
  SiteGrid g;
  g.spacing = extent(r) / (r.values.at("cells") * std::pow(2.0, level));
  g.gx = static_cast<int>(std::ceil((r.nx - 1) * r.cell / g.spacing)) + 1;
  g.gz = static_cast<int>(std::ceil((r.ny - 1) * r.cell / g.spacing)) + 1;
  return g;
}

}  // namespace

std::vector<RidgeSite> rmp_voronoi_sites(const GeneratorRequest& r, int level) {
  // A jittered grid: one site in each cell of a grid `spacing` metres wide (Worley 1996), so the
  // nearest sites of any point lie in the 5 × 5 cells around it. Each site has a probe in [½, 1].
  constexpr std::uint64_t kStream = 0x524d50ULL << 8;  // "RMP"
  const SiteGrid g = site_grid(r, level);
  const double spacing = g.spacing;
  const int gx = g.gx, gz = g.gz;
  std::vector<RidgeSite> sites;
  for (int b = -1; b <= gz; ++b)
    for (int a = -1; a <= gx; ++a) {
      const std::uint64_t id = (static_cast<std::uint64_t>(level) << 48) ^
                               (static_cast<std::uint64_t>(b + 1) << 24) ^
                               static_cast<std::uint64_t>(a + 1);
      sites.push_back({(a + uniform(r, kStream, 3 * id)) * spacing,
                       (b + uniform(r, kStream, 3 * id + 1)) * spacing,
                       0.5 + 0.5 * uniform(r, kStream, 3 * id + 2), a, b});
    }
  return sites;
}

Heightmap rmp_voronoi(const GeneratorRequest& r) {
  // Level ℓ (magnified 2^ℓ times): the distance F2 − F1 between the nearest and the second nearest
  // site is 0 on the Voronoi edges, so a tent max(0, w − (F2 − F1)) puts a ridge on every edge, as
  // high as the probes of the two sites say; each magnification adds ridges half as high and half
  // as far apart.
  const int levels = static_cast<int>(r.values.at("levels"));
  const double gain = r.values.at("gain"), width = r.values.at("width");
  std::vector<double> h(static_cast<std::size_t>(r.nx) * r.ny, 0.0);
  double amplitude = 1.0;
  for (int level = 0; level < levels; ++level, amplitude *= gain) {
    const std::vector<RidgeSite> sites = rmp_voronoi_sites(r, level);
    const SiteGrid g = site_grid(r, level);
    const double spacing = g.spacing;
    std::vector<std::pair<const RidgeSite*, double>> around;  // the 5 × 5 cells' sites, reused
    for (int j = 0; j < r.ny; ++j)
      for (int i = 0; i < r.nx; ++i) {
        const double x = i * r.cell, z = j * r.cell;
        const int ca = static_cast<int>(std::floor(x / spacing)),
                  cb = static_cast<int>(std::floor(z / spacing));
        // The nearest site A, then the highest ridge between A and any other site B:
        // probe_AB·max(0, w − (d_B − d_A)), probe_AB the mean of the two sites' probes. Taken from
        // A's side and from B's the ridge meets at the edge, so the terrain is continuous and its
        // crests are the edges.
        const RidgeSite* nearest = nullptr;
        double d_a = std::numeric_limits<double>::max();
        around.clear();
        for (int b = cb - 2; b <= cb + 2; ++b)
          for (int a = ca - 2; a <= ca + 2; ++a) {
            if (a < -1 || b < -1 || a > g.gx || b > g.gz) continue;
            const RidgeSite& s = sites[static_cast<std::size_t>(b + 1) * g.row() + (a + 1)];
            const double d = std::hypot(s.x - x, s.z - z);
            around.emplace_back(&s, d);
            if (d < d_a) d_a = d, nearest = &s;
          }
        double ridge = 0;
        for (const auto& [site, d_b] : around) {
          if (site == nearest) continue;
          ridge = std::max(ridge, 0.5 * (nearest->probe + site->probe) *
                                      std::max(0.0, width * spacing - (d_b - d_a)));
        }
        h[static_cast<std::size_t>(j) * r.nx + i] += amplitude * ridge;
      }
  }
  Heightmap t(r.nx, r.ny, r.cell);
  for (std::size_t k = 0; k < h.size(); ++k) t.h[k] = static_cast<float>(h[k]);
  normalise(t, r.values.at("relief") * extent(r));
  return t;
}

Heightmap rmp_graph(const GeneratorRequest& r) {
  // Peaks at random, joined by their minimum spanning tree (the ridge graph, Prim's algorithm);
  // repeated magnification: each ridge segment is split at its midpoint, moved sideways by a probe
  // of up to `wander` times its length, `levels` times. The ridge's height runs linearly between
  // its peaks; the terrain falls from the nearest ridge at `flank` (height per metre).
  constexpr std::uint64_t kStream = 0x524d47ULL << 8;  // "RMG"
  const double L = extent(r);
  const int peaks = static_cast<int>(r.values.at("peaks"));
  struct P {
    double x, z, h;
  };
  std::vector<P> peak(static_cast<std::size_t>(peaks));
  for (int p = 0; p < peaks; ++p)
    peak[p] = {uniform(r, kStream, 3 * p) * (r.nx - 1) * r.cell,
               uniform(r, kStream, 3 * p + 1) * (r.ny - 1) * r.cell,
               0.4 + 0.6 * uniform(r, kStream, 3 * p + 2)};
  // Prim's minimum spanning tree, ties broken by index: deterministic.
  struct Segment {
    P a, b;
  };
  std::vector<Segment> segments;
  std::vector<bool> in(peaks, false);
  std::vector<double> best(peaks, std::numeric_limits<double>::max());
  std::vector<int> from(peaks, -1);
  best[0] = 0;
  for (int step = 0; step < peaks; ++step) {
    int u = -1;
    for (int p = 0; p < peaks; ++p)
      if (!in[p] && (u < 0 || best[p] < best[u])) u = p;
    in[u] = true;
    if (from[u] >= 0) segments.push_back({peak[from[u]], peak[u]});
    for (int p = 0; p < peaks; ++p) {
      const double d = std::hypot(peak[p].x - peak[u].x, peak[p].z - peak[u].z);
      if (!in[p] && d < best[p]) best[p] = d, from[p] = u;
    }
  }
  const int levels = static_cast<int>(r.values.at("levels"));
  const double wander = r.values.at("wander");
  std::uint64_t probe = 0;
  for (int level = 0; level < levels; ++level) {
    std::vector<Segment> finer;
    for (const Segment& s : segments) {
      const double dx = s.b.x - s.a.x, dz = s.b.z - s.a.z;
      const double off = wander * (2.0 * uniform(r, kStream + 1, probe++) - 1.0);
      const P mid{0.5 * (s.a.x + s.b.x) - off * dz, 0.5 * (s.a.z + s.b.z) + off * dx,
                  0.5 * (s.a.h + s.b.h)};
      finer.push_back({s.a, mid});
      finer.push_back({mid, s.b});
    }
    segments.swap(finer);
  }
  const double flank = r.values.at("flank");
  Heightmap t = from_function(r, [&](double x, double z) {
    double height = 0;
    for (const Segment& s : segments) {
      const double dx = s.b.x - s.a.x, dz = s.b.z - s.a.z, len2 = dx * dx + dz * dz;
      const double u =
          len2 > 0 ? std::clamp(((x - s.a.x) * dx + (z - s.a.z) * dz) / len2, 0.0, 1.0) : 0.0;
      const double d = std::hypot(x - (s.a.x + u * dx), z - (s.a.z + u * dz));
      height = std::max(height, (s.a.h + u * (s.b.h - s.a.h)) * L - flank * d);
    }
    return height;
  });
  normalise(t, r.values.at("relief") * L);
  return t;
}

}  // namespace runnel::generator_util
