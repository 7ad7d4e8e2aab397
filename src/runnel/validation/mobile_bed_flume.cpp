// SPDX-License-Identifier: MIT
// The flume of the mobile-bed case as terrain, rasters and a scenario.
#include <cmath>
#include <filesystem>
#include <sstream>

#include "runnel/io/atomic_file.hpp"
#include "runnel/terrain/terrain_io.hpp"
#include "runnel/validation/mobile_bed.hpp"

namespace runnel {

namespace {

constexpr double kUpstreamEnd = -12.09, kDownstreamEnd = 15.5;  // m from the gate's centre
constexpr double kTankEnd = -10.33, kTankHalfWidth = 4.6, kTankFloor = -0.10;
constexpr double kChannelHalfWidth = 1.8, kGateHalfLength = 0.5, kGateHalfWidth = 0.5;
constexpr double kSandStart = -1.0, kSandEnd = 9.0, kSillEnd = 9.05, kSand = 0.085;
constexpr double kWall = 1.0, kReservoirLevel = 0.47;

enum class Ground { kWall, kTank, kFloor, kSand, kSill };

// What lies at (x, y); a point just inside a wall's face belongs to the water's side.
Ground ground_at(double x, double y) {
  const double e = 1e-9, ay = std::abs(y);
  if (x < kUpstreamEnd + e) return Ground::kWall;
  if (x <= kTankEnd + e) return ay < kTankHalfWidth - e ? Ground::kTank : Ground::kWall;
  if (ay > kChannelHalfWidth + e) return Ground::kWall;
  if (std::abs(x) <= kGateHalfLength + e && ay > kGateHalfWidth + e) return Ground::kWall;
  if (x >= kSandStart - e && x <= kSandEnd + e) return Ground::kSand;
  if (x > kSandEnd && x <= kSillEnd + e) return Ground::kSill;
  return Ground::kFloor;
}

}  // namespace

Flume soares_frazao_flume(double cell) {
  const int nx = static_cast<int>(std::ceil((kDownstreamEnd - kUpstreamEnd) / cell - 1e-9)) + 1;
  // A row of wall beyond the tank's sides.
  const int ny = 2 * static_cast<int>(std::ceil((kTankHalfWidth + cell) / cell - 1e-9)) + 1;
  Flume f;
  f.terrain = Heightmap(nx, ny, cell);
  // The raster's lower-left corner, half a cell outside the first vertex (MapFrame): the
  // upstream end at x = kUpstreamEnd, the flume's axis at y = 0.
  f.terrain.origin_x = kUpstreamEnd - 0.5 * cell;
  f.terrain.origin_z = -0.5 * ny * cell;
  f.sand.assign(f.terrain.size(), 0.0f);
  f.walls.assign(f.terrain.size(), 0.0f);
  const MapFrame map(f.terrain);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * nx + i;
      const Ground g = ground_at(map.x(i * cell), map.y(j * cell));
      const bool frozen = g == Ground::kWall || g == Ground::kSill;
      f.terrain.h[k] = static_cast<float>(g == Ground::kWall                         ? kWall
                                          : g == Ground::kTank                       ? kTankFloor
                                          : g == Ground::kSand || g == Ground::kSill ? kSand
                                                                                     : 0.0);
      f.sand[k] = g == Ground::kSand ? static_cast<float>(kSand) : 0.0f;
      f.walls[k] = frozen ? 1.0f : 0.0f;
    }
  return f;
}

void write_flume_scenario(const Flume& flume, const std::string& data_dir,
                          const std::string& scenario_path) {
  namespace fs = std::filesystem;
  fs::create_directories(data_dir);
  fs::create_directories(fs::absolute(scenario_path).parent_path());
  write_terrain((fs::path(data_dir) / "terrain.asc").string(), flume.terrain);
  Heightmap raster(flume.terrain.nx, flume.terrain.ny, flume.terrain.cell);
  raster.h = flume.sand;
  write_terrain((fs::path(data_dir) / "sand.npy").string(), raster);
  raster.h = flume.walls;
  write_terrain((fs::path(data_dir) / "walls.npy").string(), raster);
  // The scenario names its files relative to its own folder, as a scenario does.
  const fs::path from = fs::absolute(scenario_path).parent_path();
  auto file = [&](const char* name) {
    return fs::relative(fs::absolute(fs::path(data_dir) / name), from).generic_string();
  };
  std::ostringstream s;
  s << "# Soares-Frazão et al. (2012): dam-break flow over a mobile bed, on cells of "
    << flume.terrain.cell << " m\n"
    << "# (runnel validate mobile-bed writes it; docs/validation.md). Map coordinates: x from the\n"
    << "# gate's centre, y from the flume's axis, heights above the fixed floor.\n"
    << "[terrain]\nfile = \"" << file("terrain.asc") << "\"\n\n"
    << "[run]\nmodel = \"pipe\"\nsim_time = 20\nprobe_every = 0.1\nreport_every = 1000\n\n"
    << "[pipe]\nflux = \"godunov\"\nlaw = \"bedload\"\nrain = 0\nevaporation = 0\n"
    << "# Strickler's n for the grains, d^(1/6) / 21.1\nmanning_n = 0.0162\n"
    << "# The first-order Godunov flux is stable to 0.5 in two dimensions: 0.45 gives the same "
       "gauges\n"
    << "# and bed to 0.1 mm as the default 0.25 in 56 % of the steps (docs/validation.md).\ncfl = "
       "0.45\n\n"
    << "[sediment]\ngrain_diameter = 0.00161\ngrain_density = 2630\nporosity = 0.42\n\n"
    << "# The sand slides at its submerged angle of repose.\n"
    << "[thermal]\ninterval = 0.1\ntalus_angle = 32\n\n"
    << "# For `runnel compare --models pipe,sph`: SPH without rain, with the bed-load law, its\n"
    << "# particles a cell apart, incompressible (the weakly compressible solver's first step\n"
    << "# overshoots the density at the flume's 1 m walls).\n"
    << "[rain]\nenabled = false\n\n[sph]\nspacing = " << flume.terrain.cell
    << "\nsolver = \"dfsph\"\n\n[erosion]\nmodel = \"bedload\"\n\n"
    << "[ground]\nbedrock_erodibility = 0\nfrozen_mask = \"" << file("walls.npy") << "\"\n\n"
    << "[[layers]]\nname = \"sand\"\nthickness_file = \"" << file("sand.npy") << "\"\n\n"
    << "# The reservoir, up to the gate.\n"
    << "[[water.bodies]]\nx0 = " << kUpstreamEnd << "\nx1 = 0\ny0 = " << -kTankHalfWidth
    << "\ny1 = " << kTankHalfWidth << "\nlevel = " << kReservoirLevel << "\n";
  for (const MobileBedGauge& g : soares_frazao_gauges())
    for (double side : {1.0, -1.0})
      s << "\n[[probes]]\nname = \"" << g.name << (side > 0 ? "" : "_mirror") << "\"\nx = " << g.x
        << "\ny = " << side * g.y << "\n";
  write_text_atomically(scenario_path, s.str());
}

double outside_band(double value, double low, double high) {
  return value < low ? low - value : value > high ? value - high : 0.0;
}

}  // namespace runnel
