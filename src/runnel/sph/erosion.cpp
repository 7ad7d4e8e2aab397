// SPDX-License-Identifier: MIT
#include "runnel/sph/erosion.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/compute/build_options.hpp"
#include "runnel/compute/launch.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/parameter_groups.hpp"
#include "runnel/core/settings_table.hpp"
#include "runnel/core/text.hpp"

namespace runnel {

namespace {

// clang-format off
const SettingsTable<ErosionSettings> kErosionTable = {
      // erosion: dissolving and depositing sediment (physics.md §4)
      {"erosion.model", "\"stream-power\"", "", 0, 0, {"stream-power", "acidity", "bedload"}, "stream-power: detachment driven by the power the flow spends on its bed against a transport capacity, coupled as Foster & Meyer 1975 (docs/erosion.md); acidity: Fritz 2016's fixed erosion per contact; bedload: Wong & Parker's Meyer-Peter & Müller from the Shields stress of the bed shear, each particle's load relaxing to the bed load its flow carries over sediment.adaptation_length (sediment.* gives the grains)", &ErosionSettings::model},
      {"erosion.erodibility", "0.001", "s^2/m^2", 0, 1e6, {}, "K_ω: detachment K_ω (ω − ω_c) in kg/m²/s, ω the stream power on the bed in W/m²", &ErosionSettings::erodibility},
      {"erosion.critical_power", "0", "W/m^2", 0, 1e9, {}, "ω_c, the stream power below which the flow detaches nothing", &ErosionSettings::critical_power, "EROSION_CRITICAL_POWER"},
      {"erosion.transport_efficiency", "0.02", "s^2/m", 0, 1e6, {}, "k_T: transport capacity k_T ω per unit width (kg/m/s, ω the stream power; Bagnold 1966: about 0.16 × his efficiency, 0.01–0.15), carried as the concentration k_T ρ0 g S / ρ_b (S the sine of the slope)", &ErosionSettings::transport},
      {"erosion.settling_velocity", "0.01", "m/s", 0, 100, {}, "w_s, the fall velocity of the sediment (fine sand about 0.01): deposition w_s (c − c_T)", &ErosionSettings::settling, "EROSION_SETTLING"},
      {"erosion.bed_density", "1600", "kg/m^3", 1, 1e5, {}, "ρ_b, dry bulk density of the bed: converts mass rates into bed volume", &ErosionSettings::bed_density},
      {"erosion.max_concentration", "0.2", "1", 0, 1, {}, "c_max, the most bed volume a particle carries per volume of its water", &ErosionSettings::max_concentration, "EROSION_MAX_CONCENTRATION"},
      {"erosion.morphological_factor", "1", "1", 0, 1e9, {}, "morphological acceleration (Roelvink 2006): the bed changes as over this many seconds for each second of flow; detachment, transport capacity and the load limit scale with it, the water does not", &ErosionSettings::morphological_factor},
      {"erosion.acidity", "0.001", "m", 0, 1e3, {}, "acidity model: depth eroded per contact (× cell²)", &ErosionSettings::acidity, "EROSION_ACIDITY"},
      {"erosion.capacity_contacts", "10", "1", 0, 1e9, {}, "acidity model: erosion events per particle", &ErosionSettings::capacity_contacts},
      {"erosion.deposit_fraction", "1", "1", 0, 1, {}, "share of the load deposited on evaporation; < 1 reproduces Fritz 2016 and books the rest as lost (non-conserving)", &ErosionSettings::deposit_fraction, "EROSION_DEPOSIT_FRACTION"},
      {"erosion.height_quantum", "1e-6", "m", 1e-12, 1, {}, "fixed-point quantum of terrain heights; sediment is counted in quantum · cell²", &ErosionSettings::height_quantum},
      {"erosion.exchange_interval", "0", "s", 0, 1e3, {}, "stream-power model: the bed exchanges with the water once every this many simulated seconds, each particle on the bed over the whole interval (the bed changes far more slowly than the fluid's time step, which the speed of sound sets; docs/erosion.md, \"Exchange interval\"); 0: every step", &ErosionSettings::exchange_interval},
};
// clang-format on

}  // namespace

std::vector<ParamSpec> erosion_parameters() {
  return settings_specs(kErosionTable);
}

ErosionSettings ErosionSettings::from(const Parameters& p, const SphSettings& sph,
                                      double terrain_cell) {
  ErosionSettings e = read_settings(p, kErosionTable);
  // Fritz's acidity model erodes a fixed amount per contact, and a contact is a step's: fewer
  // exchanges would erode less, not the same over longer intervals.
  if (e.model == "acidity" && e.exchange_interval > 0) {
    throw input_error("erosion.exchange_interval: " + format_number(e.exchange_interval) +
                      " s applies to the stream-power model only (the acidity model erodes per "
                      "contact of a step); use 0 with erosion.model = \"acidity\"");
  }
  e.footprint_radius = runnel::footprint_radius(sph, terrain_cell);
  e.sediment = SedimentSettings::from(p);
  return e;
}

std::string ErosionSettings::build_options(const SphSettings& sph, double volume_quantum) const {
  // The raw values from the table; then what the kernel needs combined with the fluid's.
  std::string o = settings_defines(*this, kErosionTable);
  o += std::string(" -DEROSION_MODEL=") + (model == "acidity"   ? "1"
                                           : model == "bedload" ? "2"
                                                                : "0");
  if (model == "bedload")
    o += sediment.build_options() + float_define("EROSION_GRAVITY", sph.gravity) +
         float_define("EROSION_RHO0", sph.rho0);
  const double volume = sph.spacing * sph.spacing * sph.spacing;
  o += float_define("EROSION_RHO_G_N2", sph.rho0 * sph.gravity * sph.manning_n * sph.manning_n);
  o += float_define("EROSION_DETACHMENT", erodibility / bed_density);
  o += float_define("EROSION_TRANSPORT_SLOPE", transport * sph.rho0 * sph.gravity / bed_density);
  o += float_define("EROSION_PARTICLE_RADIUS", sph.contact_radius);
  o += float_define("EROSION_PARTICLE_VOLUME", volume);
  o += float_define("FOOTPRINT_RADIUS", footprint_radius);
  o += " -DEROSION_CAPACITY_CONTACTS=" + std::to_string(capacity_contacts) + "u";
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
      .add("height_quantum_m", height_quantum)
      .add("exchange_interval_s", exchange_interval);
}

Erosion::Erosion(ComputeContext& compute, const ErosionSettings& settings, const SphSolver& solver,
                 std::uint64_t seed, const BedFields* bed)
    : settings_(settings), seed_(seed) {
  const std::string options =
      settings.build_options(solver.settings(), settings.height_quantum * solver.terrain_cell() *
                                                    solver.terrain_cell()) +
      (bed ? " -DGROUND=1" : "");
  kernel_ = Kernel(compute,
                   compute.program({"cl/common.cl", "cl/counters.cl", "cl/grid.cl",
                                    "cl/terrain_sample.cl", "cl/footprint.cl", "cl/erode.cl"},
                                   options),
                   "erode_exchange");
  placeholder_ = placeholder_buffer(compute);
  kernel_.set("erodibility", bed ? bed->erodibility : placeholder_);
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
      .set("counters", solver.counters_buffer());
  solver.terrain().bind_changes(k);
  k.launch(round_up_work(n));
}

}  // namespace runnel
