// SPDX-License-Identifier: MIT
#include "runnel/sph/rain_emitter.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/compute/launch.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/parameter_groups.hpp"
#include "runnel/core/rain_units.hpp"
#include "runnel/core/settings_table.hpp"

namespace runnel {

namespace {

// clang-format off
const SettingsTable<RainSettings> kRainTable = {
      // rain: the emitter (physics.md §4)
      {"rain.region", "\"terrain\"", "", 0, 0, {"terrain", "rectangle", "disc"}, "where rain falls: the whole terrain, rain.rect_*, or the disc rain.disc_*", &RainSettings::region_name},
      {"rain.rect_x0", "0", "m", -1e9, 1e9, {}, "rectangle: west edge (x)", &RainSettings::rect_x0},
      {"rain.rect_x1", "0", "m", -1e9, 1e9, {}, "rectangle: east edge (x)", &RainSettings::rect_x1},
      {"rain.rect_z0", "0", "m", -1e9, 1e9, {}, "rectangle: north edge (z)", &RainSettings::rect_z0},
      {"rain.rect_z1", "0", "m", -1e9, 1e9, {}, "rectangle: south edge (z)", &RainSettings::rect_z1},
      {"rain.disc_x", "0", "m", -1e9, 1e9, {}, "disc: centre x", &RainSettings::disc_x},
      {"rain.disc_z", "0", "m", -1e9, 1e9, {}, "disc: centre z", &RainSettings::disc_z},
      {"rain.disc_radius", "0", "m", 0, 1e9, {}, "disc: radius", &RainSettings::disc_radius},
      {"rain.rate", "0", "particles/s", 0, 1e9, {}, "particles spawned per second; 0: from rain.intensity, or if that is 0 too, max_particles / lifespan", &RainSettings::rate},
      {"rain.intensity", "0", "mm/h", 0, 1e9, {}, "rain intensity over the region (converted through the particle volume dx³); used when rain.rate is 0", &RainSettings::intensity_mm_h},
      {"rain.spawn_height", "0", "m", 0, 1e6, {}, "height above the terrain where drops appear; 0: 1 dx", &RainSettings::spawn_height},
      {"rain.above_water", "false", "", 0, 0, {}, "drops appear rain.spawn_height above the water's surface (the terrain plus the water depth on its vertices, as the last step measured it) rather than above the terrain: rain enters ponds and sheets at their surface instead of inside them", &RainSettings::above_water},
      {"rain.speed", "0", "m/s", 0, 1e4, {}, "initial downward speed of a drop", &RainSettings::speed},
      {"rain.max_particles", "0", "particles", 0, 1e8, {}, "particle budget: the emitter never lets more particles live at once (drops it holds back are counted, reported in metrics.json and cautioned about); 0: follow the storm (rain.rate or rain.intensity times the longest lifespan, within the device's memory), or 20000 when neither is given", &RainSettings::max_particles},
      {"rain.lifespan", "0", "s", 0, 1e9, {}, "mean lifespan of a drop before it evaporates; 0: the time to cross the terrain at a tenth of the reference speed (water under bed friction runs slower than a free fall)", &RainSettings::lifespan},
      {"rain.lifespan_jitter", "0.25", "1", 0, 0.99, {}, "lifespans are uniform in mean·(1 ± jitter)", &RainSettings::lifespan_jitter},
      {"rain.enabled", "true", "", 0, 0, {}, "rain on or off", &RainSettings::enabled},
};
// clang-format on

}  // namespace

std::vector<ParamSpec> rain_parameters() {
  return settings_specs(kRainTable);
}

double RainSettings::spawn_height_of(const Parameters& p, double spacing) {
  const double given = p.real("rain.spawn_height");
  return given > 0 ? given : spacing;
}

RainSettings RainSettings::from(const Parameters& p, const DeviceTerrain& terrain, double spacing,
                                double reference_speed) {
  RainSettings r = read_settings(p, kRainTable);
  const double lx = terrain.extent_x(), lz = terrain.extent_z();
  if (r.region_name == "rectangle") {
    r.region = Region::kRectangle;
    r.a = r.rect_x0, r.b = r.rect_x1, r.c = r.rect_z0, r.d = r.rect_z1;
    if (!(r.b > r.a) || !(r.d > r.c))
      throw input_error("rain.rect_x1, rain.rect_z1: the rectangle is empty");
    if (r.a < 0 || r.c < 0 || r.b > lx || r.d > lz) {
      throw input_error("rain.rect_*: the rectangle leaves the terrain [0, " + std::to_string(lx) +
                        "] x [0, " + std::to_string(lz) + "] m");
    }
    r.area = (r.b - r.a) * (r.d - r.c);
  } else if (r.region_name == "disc") {
    r.region = Region::kDisc;
    r.a = r.disc_x, r.c = r.disc_z, r.b = r.disc_radius;
    if (!(r.b > 0))
      throw input_error("rain.disc_radius: must be positive for rain.region = \"disc\"");
    // The nearest point of the terrain to the centre must lie inside the disc.
    const double dx = r.a - std::clamp(r.a, 0.0, lx), dz = r.c - std::clamp(r.c, 0.0, lz);
    if (std::hypot(dx, dz) >= r.b) {
      throw input_error(
          "rain.disc_x, rain.disc_z, rain.disc_radius: the disc lies entirely off the "
          "terrain [0, " +
          std::to_string(lx) + "] x [0, " + std::to_string(lz) + "] m");
    }
    r.area = M_PI * r.b * r.b;
  } else {
    r.region = Region::kTerrain;
    r.area = lx * lz;
  }
  r.spawn_height = spawn_height_of(p, spacing);
  // By default a drop lives long enough to cross the terrain at a tenth of the reference speed:
  // water under bed friction runs several times slower than a free fall over the relief.
  if (!(r.lifespan > 0)) r.lifespan = 10.0 * std::max(lx, lz) / reference_speed;
  const double volume = spacing * spacing * spacing;
  const bool storm_given = r.rate > 0 || r.intensity_mm_h > 0;
  if (r.max_particles == 0 && !storm_given) r.max_particles = kDefaultRainBudget;
  if (!(r.rate > 0)) {
    r.rate = r.intensity_mm_h > 0 ? rain_depth_rate(r.intensity_mm_h) * r.area / volume
                                  : static_cast<double>(r.max_particles) / r.lifespan;
  }
  r.intensity_mm_h = rain_intensity(r.rate * volume / r.area);
  if (r.max_particles == 0) {
    // No more drops can live at once than fall during the longest lifespan.
    r.budget_follows_storm = true;
    r.max_particles = static_cast<std::int64_t>(std::min(1e8, r.most_alive()));
  }
  return r;
}

void RainSettings::rain_on_disc(double x, double z, double radius, double intensity,
                                double spacing) {
  region_name = "disc";
  region = Region::kDisc;
  a = disc_x = x;
  c = disc_z = z;
  b = disc_radius = radius;
  area = M_PI * radius * radius;
  intensity_mm_h = intensity;
  rate = rain_depth_rate(intensity) * area / (spacing * spacing * spacing);
  enabled = true;
}

JsonObject RainSettings::json() const {
  const char* names[] = {"terrain", "rectangle", "disc", "terrain by the rain mask"};
  return JsonObject()
      .add("region", names[static_cast<int>(region)])
      .add("area_m2", area)
      .add("rate_particles_per_s", rate)
      .add("intensity_mm_per_h", intensity_mm_h)
      .add("spawn_height_m", spawn_height)
      .add("speed_m_per_s", speed)
      .add("max_particles", max_particles)
      .add("budget_follows_storm", budget_follows_storm)
      .add("lifespan_s", lifespan)
      .add("lifespan_jitter", lifespan_jitter)
      .add("enabled", enabled);
}

RainEmitter::RainEmitter(ComputeContext& compute, const RainSettings& settings, std::uint64_t seed,
                         float rest_density, const std::vector<float>& rain_weights, int nx)
    : compute_(compute),
      settings_(settings),
      seed_(seed),
      rest_density_(rest_density),
      kernel_(compute,
              compute.program({"cl/common.cl", "cl/grid.cl", "cl/terrain_sample.cl", "cl/rain.cl"}),
              "rain_emit") {
  unmasked_ = masked_ = settings_;
  std::vector<float> cdf(1, 1.0f);
  if (!rain_weights.empty()) {
    if (settings_.region != RainSettings::Region::kTerrain)
      throw input_error(
          "ground.rain_mask: a rain mask shapes the rain of the whole terrain; "
          "use it with rain.region = \"terrain\"");
    cells_ = (nx - 1) * (static_cast<int>(rain_weights.size()) / nx - 1);
  }
  cell_cdf_ = cl::Buffer(compute.context(), CL_MEM_READ_WRITE, cells_ * sizeof(float));
  compute.queue().enqueueWriteBuffer(cell_cdf_, CL_TRUE, 0, sizeof(float), cdf.data());
  if (!rain_weights.empty()) set_weights(rain_weights, nx);
  kernel_.set("cell_cdf", cell_cdf_).set("cells", static_cast<cl_int>(cells_));
}

void RainEmitter::set_weights(const std::vector<float>& rain_weights, int nx) {
  const auto [cdf, fraction] =
      rain_cell_cdf(rain_weights, nx, static_cast<int>(rain_weights.size()) / nx);
  if (cdf.size() != static_cast<std::size_t>(cells_)) {  // a first mask, set while running
    cells_ = static_cast<int>(cdf.size());
    cell_cdf_ = cl::Buffer(compute_.context(), CL_MEM_READ_WRITE, cdf.size() * sizeof(float));
    kernel_.set("cell_cdf", cell_cdf_).set("cells", static_cast<cl_int>(cells_));
  }
  masked_ = unmasked_;
  masked_.region = RainSettings::Region::kMask;
  masked_.rate *= fraction;
  masked_.intensity_mm_h *= fraction;  // the mean over the terrain
  // At construction the settings are the scenario's (the whole terrain); later only the mask's
  // own rain follows (a brush's disc stays as it is).
  if (settings_.region == RainSettings::Region::kMask || settings_.region == unmasked_.region) {
    const bool enabled = settings_.enabled;
    settings_ = masked_;
    settings_.enabled = enabled;
  }
  compute_.queue().enqueueWriteBuffer(cell_cdf_, CL_TRUE, 0, cdf.size() * sizeof(float),
                                      cdf.data());
}

std::pair<std::vector<float>, double> rain_cell_cdf(const std::vector<float>& weights, int nx,
                                                    int ny) {
  const int cx = nx - 1, cz = ny - 1;
  std::vector<double> cell(static_cast<std::size_t>(cx) * cz);
  double total = 0;
  for (int j = 0; j < cz; ++j) {
    for (int i = 0; i < cx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * nx + i;
      const double w =
          0.25 * (double(weights[k]) + weights[k + 1] + weights[k + nx] + weights[k + nx + 1]);
      cell[static_cast<std::size_t>(j) * cx + i] = w;
      total += w;
    }
  }
  std::vector<float> cdf(cell.size(), 1.0f);
  if (total <= 0) return {cdf, 0.0};
  double sum = 0;
  for (std::size_t m = 0; m < cell.size(); ++m) {
    sum += cell[m];
    cdf[m] = static_cast<float>(sum / total);
  }
  cdf.back() = 1.0f;
  return {cdf, total / static_cast<double>(cell.size())};
}

std::size_t RainEmitter::emit(SphSolver& solver, double dt) {
  if (!settings_.enabled || settings_.rate <= 0) return 0;
  carry_ += settings_.rate * dt;
  const double whole = std::floor(carry_);
  carry_ -= whole;
  ParticleStore& store = solver.particles();
  const long long room =
      std::max(0LL, settings_.max_particles - static_cast<long long>(store.size()));
  const std::size_t count =
      static_cast<std::size_t>(std::min<double>(whole, static_cast<double>(room)));
  held_back_ += static_cast<std::uint64_t>(whole) - count;
  if (count == 0) return 0;
  const cl_uint first_id = store.next_id();
  const std::size_t first = store.extend(count);
  Kernel& k = kernel_;
  store.bind(k, {kX, kY, kZ, kVx, kVy, kVz, kRho, kSediment, kAge, kLifespan, kContacts, kId});
  solver.terrain().bind(k);
  k.set("water", solver.water_field()).set("above_water", cl_int{settings_.above_water});
  k.set("first_index", static_cast<cl_uint>(first))
      .set("count", static_cast<cl_uint>(count))
      .set("seed", static_cast<cl_ulong>(seed_))
      .set("first_counter", static_cast<cl_ulong>(spawned_))
      .set("first_id", first_id)
      .set("region", static_cast<cl_int>(settings_.region))
      .set("rho0", rest_density_);
  const std::pair<const char*, double> reals[] = {
      {"a", settings_.a},
      {"b", settings_.b},
      {"c", settings_.c},
      {"d", settings_.d},
      {"spawn_height", settings_.spawn_height},
      {"contact_radius", solver.settings().contact_radius},
      {"surface_eps", solver.settings().surface_eps},
      {"speed", settings_.speed},
      {"lifespan_mean", settings_.lifespan},
      {"lifespan_jitter", settings_.lifespan_jitter},
      // dfsph's steps are long (30–50 ms where wcsph's are 2–3): its drops fall from their own
      // times within the step, not all from the spawn height at its end.
      {"spread", solver.settings().incompressible() ? dt : 0.0},
      {"gravity", solver.settings().gravity}};
  for (const auto& [name, value] : reals) k.set(name, static_cast<float>(value));
  k.launch(round_up_work(count));
  spawned_ += count;
  return count;
}

}  // namespace runnel
