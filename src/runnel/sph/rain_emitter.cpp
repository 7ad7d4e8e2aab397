// SPDX-License-Identifier: MIT
#include "runnel/sph/rain_emitter.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/compute/launch.hpp"
#include "runnel/core/error.hpp"

namespace runnel {

RainSettings RainSettings::from(const Parameters& p, const DeviceTerrain& terrain, double spacing,
                                double reference_speed) {
  RainSettings r;
  const std::string region = p.text("rain.region");
  const double lx = terrain.extent_x(), lz = terrain.extent_z();
  if (region == "rectangle") {
    r.region = Region::kRectangle;
    r.a = p.real("rain.rect_x0");
    r.b = p.real("rain.rect_x1");
    r.c = p.real("rain.rect_z0");
    r.d = p.real("rain.rect_z1");
    if (!(r.b > r.a) || !(r.d > r.c))
      throw input_error("rain.rect_x1, rain.rect_z1: the rectangle is empty");
    if (r.a < 0 || r.c < 0 || r.b > lx || r.d > lz) {
      throw input_error("rain.rect_*: the rectangle leaves the terrain [0, " + std::to_string(lx) +
                        "] x [0, " + std::to_string(lz) + "] m");
    }
    r.area = (r.b - r.a) * (r.d - r.c);
  } else if (region == "disc") {
    r.region = Region::kDisc;
    r.a = p.real("rain.disc_x");
    r.c = p.real("rain.disc_z");
    r.b = p.real("rain.disc_radius");
    if (!(r.b > 0))
      throw input_error("rain.disc_radius: must be positive for rain.region = \"disc\"");
    r.area = M_PI * r.b * r.b;
  } else {
    r.area = lx * lz;
  }
  r.enabled = p.boolean("rain.enabled");
  r.max_particles = p.integer("rain.max_particles");
  r.spawn_height = p.real("rain.spawn_height") > 0 ? p.real("rain.spawn_height") : spacing;
  r.speed = p.real("rain.speed");
  // By default a drop lives long enough to cross the terrain at a tenth of the reference speed:
  // water under bed friction runs several times slower than a free fall over the relief.
  r.lifespan = p.real("rain.lifespan") > 0 ? p.real("rain.lifespan")
                                           : 10.0 * std::max(lx, lz) / reference_speed;
  r.lifespan_jitter = p.real("rain.lifespan_jitter");
  const double volume = spacing * spacing * spacing;
  if (p.real("rain.rate") > 0) {
    r.rate = p.real("rain.rate");
  } else if (p.real("rain.intensity") > 0) {
    r.rate = p.real("rain.intensity") / 1000.0 / 3600.0 * r.area / volume;
  } else {
    r.rate = static_cast<double>(r.max_particles) / r.lifespan;
  }
  r.intensity_mm_h = r.rate * volume / r.area * 1000.0 * 3600.0;
  return r;
}

JsonObject RainSettings::json() const {
  const char* names[] = {"terrain", "rectangle", "disc"};
  return JsonObject()
      .add("region", names[static_cast<int>(region)])
      .add("area_m2", area)
      .add("rate_particles_per_s", rate)
      .add("intensity_mm_per_h", intensity_mm_h)
      .add("spawn_height_m", spawn_height)
      .add("speed_m_per_s", speed)
      .add("max_particles", max_particles)
      .add("lifespan_s", lifespan)
      .add("lifespan_jitter", lifespan_jitter)
      .add("enabled", enabled);
}

RainEmitter::RainEmitter(ComputeContext& compute, const RainSettings& settings, std::uint64_t seed,
                         float rest_density)
    : compute_(compute),
      settings_(settings),
      seed_(seed),
      rest_density_(rest_density),
      kernel_(compute,
              compute.program({"cl/common.cl", "cl/grid.cl", "cl/terrain_sample.cl", "cl/rain.cl"}),
              "rain_emit") {}

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
  if (count == 0) return 0;
  const cl_uint first_id = store.next_id();
  const std::size_t first = store.extend(count);
  Kernel& k = kernel_;
  store.bind(k, {kX, kY, kZ, kVx, kVy, kVz, kRho, kSediment, kAge, kLifespan, kContacts, kId});
  solver.terrain().bind(k);
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
      {"lifespan_jitter", settings_.lifespan_jitter}};
  for (const auto& [name, value] : reals) k.set(name, static_cast<float>(value));
  k.launch(round_up_work(count));
  spawned_ += count;
  return count;
}

}  // namespace runnel
