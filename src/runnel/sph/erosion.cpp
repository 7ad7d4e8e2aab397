// SPDX-License-Identifier: MIT
#include "runnel/sph/erosion.hpp"

#include <cmath>
#include <cstdio>

#include "runnel/compute/build_options.hpp"
#include "runnel/compute/launch.hpp"

namespace runnel {
ErosionSettings ErosionSettings::from(const Parameters& p, double spacing) {
  ErosionSettings e;
  e.model = p.text("erosion.model");
  e.capacity = p.real("erosion.capacity");
  e.erode_rate = p.real("erosion.erode_rate");
  e.deposit_rate = p.real("erosion.deposit_rate");
  e.min_slope_deg = p.real("erosion.min_slope");
  e.time_scale = p.real("erosion.time_scale");
  // Measured from the particle's surface: a particle is a sphere of radius dx/2 around its centre.
  e.contact_distance = (0.5 + p.real("erosion.contact_distance")) * spacing;
  e.limit_fraction = p.real("erosion.limit_fraction");
  e.acidity = p.real("erosion.acidity");
  e.capacity_contacts = p.integer("erosion.capacity_contacts");
  e.deposit_fraction = p.real("erosion.deposit_fraction");
  e.height_quantum = p.real("erosion.height_quantum");
  e.depth_exponent = p.real("erosion.depth_exponent");
  const double support = 2.0 * p.real("sph.h_factor");  // 2h in units of dx
  e.layer_neighbours = M_PI * support * support - 1.0;
  return e;
}

std::string ErosionSettings::build_options(double particle_volume, double volume_quantum) const {
  std::string o = std::string(" -DEROSION_MODEL=") + (model == "acidity" ? "1" : "0");
  o += float_define("EROSION_CAPACITY", capacity);
  o += float_define("EROSION_ERODE_RATE", erode_rate);
  o += float_define("EROSION_DEPOSIT_RATE", deposit_rate);
  o += float_define("EROSION_SIN_MIN_SLOPE", std::sin(min_slope_deg * M_PI / 180.0));
  o += float_define("EROSION_CONTACT_DISTANCE", contact_distance);
  o += float_define("EROSION_LIMIT_FRACTION", limit_fraction);
  o += float_define("EROSION_ACIDITY", acidity);
  o += " -DEROSION_CAPACITY_CONTACTS=" + std::to_string(capacity_contacts) + "u";
  o += float_define("EROSION_DEPOSIT_FRACTION", deposit_fraction);
  o += float_define("EROSION_PARTICLE_VOLUME", particle_volume);
  o += float_define("EROSION_VOLUME_QUANTUM", volume_quantum);
  o += float_define("EROSION_DEPTH_EXPONENT", depth_exponent);
  o += float_define("EROSION_LAYER_NEIGHBOURS", layer_neighbours);
  return o;
}

JsonObject ErosionSettings::json() const {
  return JsonObject()
      .add("model", model)
      .add("capacity_s_per_m", capacity)
      .add("erode_rate_per_s", erode_rate)
      .add("deposit_rate_per_s", deposit_rate)
      .add("min_slope_deg", min_slope_deg)
      .add("time_scale", time_scale)
      .add("contact_distance_m", contact_distance)
      .add("limit_fraction", limit_fraction)
      .add("deposit_fraction", deposit_fraction)
      .add("height_quantum_m", height_quantum)
      .add("depth_exponent", depth_exponent)
      .add("layer_neighbours", layer_neighbours);
}

Erosion::Erosion(ComputeContext& compute, const ErosionSettings& settings, const SphSolver& solver)
    : compute_(compute), settings_(settings) {
  const double volume =
      solver.settings().spacing * solver.settings().spacing * solver.settings().spacing;
  const std::string options = settings.build_options(
      volume, settings.height_quantum * solver.terrain_cell() * solver.terrain_cell());
  kernel_ = cl::Kernel(compute.program({"cl/common.cl", "cl/counters.cl", "cl/grid.cl",
                                        "cl/terrain_sample.cl", "cl/erode.cl"},
                                       options),
                       "erode_exchange");
}

void Erosion::exchange(SphSolver& solver, double dt) {
  ParticleStore& store = solver.particles();
  const cl_uint n = static_cast<cl_uint>(store.size());
  if (n == 0) return;
  cl::Kernel& k = kernel_;
  cl_uint a = 0;
  for (ParticleField f :
       {kX, kY, kZ, kVx, kVy, kVz, kSediment, kContacts, kAge, kLifespan, kId, kNeighbours}) {
    k.setArg(a++, store.buffer(f));
  }
  k.setArg(a++, n);
  k.setArg(a++, static_cast<float>(dt * settings_.time_scale));
  solver.terrain().set_args(k, a);
  a += 5;
  k.setArg(a++, solver.terrain().delta());
  k.setArg(a++, solver.counters_buffer());
  compute_.profiler().launch(k, round_up_work(n), "erode_exchange");
}

}  // namespace runnel
