// SPDX-License-Identifier: MIT
#include "runnel/sph/erosion.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/compute/build_options.hpp"
#include "runnel/compute/launch.hpp"
#include "runnel/core/error.hpp"

namespace runnel {

ErosionSettings ErosionSettings::from(const Parameters& p, const SphSettings& sph,
                                      double terrain_cell) {
  ErosionSettings e;
  e.model = p.text("erosion.model");
  e.erodibility = p.real("erosion.erodibility");
  e.critical_power = p.real("erosion.critical_power");
  e.transport = p.real("erosion.transport_efficiency");
  e.settling = p.real("erosion.settling_velocity");
  e.bed_density = p.real("erosion.bed_density");
  e.max_concentration = p.real("erosion.max_concentration");
  e.morphological_factor = p.real("erosion.morphological_factor");
  e.footprint_radius = runnel::footprint_radius(sph, terrain_cell);
  e.acidity = p.real("erosion.acidity");
  e.capacity_contacts = p.integer("erosion.capacity_contacts");
  e.deposit_fraction = p.real("erosion.deposit_fraction");
  e.height_quantum = p.real("erosion.height_quantum");
  return e;
}

std::string ErosionSettings::build_options(const SphSettings& sph, double volume_quantum) const {
  std::string o = std::string(" -DEROSION_MODEL=") + (model == "acidity" ? "1" : "0");
  const double volume = sph.spacing * sph.spacing * sph.spacing;
  o += float_define("EROSION_RHO_G_N2", sph.rho0 * sph.gravity * sph.manning_n * sph.manning_n);
  o += float_define("EROSION_CRITICAL_POWER", critical_power);
  o += float_define("EROSION_DETACHMENT", erodibility / bed_density);
  o += float_define("EROSION_TRANSPORT_SLOPE", transport * sph.rho0 * sph.gravity / bed_density);
  o += float_define("EROSION_MAX_CONCENTRATION", max_concentration);
  o += float_define("EROSION_SETTLING", settling);
  o += float_define("EROSION_PARTICLE_RADIUS", sph.contact_radius);
  o += float_define("EROSION_PARTICLE_VOLUME", volume);
  o += float_define("FOOTPRINT_RADIUS", footprint_radius);
  o += float_define("EROSION_ACIDITY", acidity);
  o += " -DEROSION_CAPACITY_CONTACTS=" + std::to_string(capacity_contacts) + "u";
  o += float_define("EROSION_DEPOSIT_FRACTION", deposit_fraction);
  o += float_define("EROSION_VOLUME_QUANTUM", volume_quantum);
  return o;
}

JsonObject ErosionSettings::json() const {
  return JsonObject()
      .add("model", model)
      .add("erodibility_s2_per_m2", erodibility)
      .add("critical_power_w_per_m2", critical_power)
      .add("transport_efficiency_s2_per_m", transport)
      .add("settling_velocity_m_per_s", settling)
      .add("bed_density_kg_per_m3", bed_density)
      .add("max_concentration", max_concentration)
      .add("morphological_factor", morphological_factor)
      .add("footprint_radius_m", footprint_radius)
      .add("deposit_fraction", deposit_fraction)
      .add("height_quantum_m", height_quantum);
}

Erosion::Erosion(ComputeContext& compute, const ErosionSettings& settings, const SphSolver& solver,
                 std::uint64_t seed)
    : compute_(compute), settings_(settings), seed_(seed) {
  const std::string options = settings.build_options(
      solver.settings(), settings.height_quantum * solver.terrain_cell() * solver.terrain_cell());
  kernel_ = Kernel(compute,
                   compute.program({"cl/common.cl", "cl/counters.cl", "cl/grid.cl",
                                    "cl/terrain_sample.cl", "cl/footprint.cl", "cl/erode.cl"},
                                   options),
                   "erode_exchange");
}

void Erosion::exchange(SphSolver& solver, double dt) {
  ParticleStore& store = solver.particles();
  const cl_uint n = static_cast<cl_uint>(store.size());
  if (n == 0) return;
  Kernel& k = kernel_;
  store.bind(k, {kX, kY, kZ, kVx, kVy, kVz, kSediment, kContacts, kAge, kLifespan, kId, kDepth});
  solver.terrain().bind(k);
  k.set("dt", static_cast<float>(dt))
      .set("morphological_factor", static_cast<float>(settings_.morphological_factor))
      .set("seed", static_cast<cl_ulong>(seed_))
      .set("step_index", static_cast<cl_ulong>(solver.steps()))
      .set("delta", solver.terrain().delta())
      .set("counters", solver.counters_buffer());
  k.launch(round_up_work(n));
}

}  // namespace runnel
