// SPDX-License-Identifier: MIT
#include "runnel/ground/bedload.hpp"

#include <cmath>

#include "runnel/core/parameter_groups.hpp"
#include "runnel/core/settings_table.hpp"
#include "runnel/core/text.hpp"

namespace runnel {
namespace {

using S = SedimentSettings;
// clang-format off
const SettingsTable<SedimentSettings> kSedimentTable = {
      // sediment: the bed's grains, for the bed-load law (pipe.law = "bedload")
      {"sediment.grain_diameter", "0.001", "m", 1e-6, 1, {}, "D, the grains' median diameter", &S::grain_diameter, "SED_GRAIN_DIAMETER"},
      {"sediment.grain_density", "2650", "kg/m3", 1001, 2e4, {}, "ρs, the grains' density (quartz 2650)", &S::grain_density, "SED_GRAIN_DENSITY"},
      {"sediment.porosity", "0.4", "1", 0, 0.9, {}, "p, the bed's porosity: a volume V of grains moves V / (1 − p) of bed (Exner)", &S::porosity, "SED_POROSITY"},
      {"sediment.critical_shields", "0.0495", "1", 0, 1, {}, "θc, the Shields stress below which grains do not move (Wong & Parker 2006: 0.0495; Meyer-Peter & Müller: 0.047)", &S::critical_shields, "SED_CRITICAL_SHIELDS"},
      {"sediment.adaptation_length", "0.05", "m", 1e-6, 1e3, {}, "SPH's bed load (erosion.model = \"bedload\"): the distance a particle's load takes to reach the flow's bed-load capacity (grains pick up and settle over a few saltation lengths)", &S::adaptation_length, "SED_ADAPTATION_LENGTH"},
};
// clang-format on

}  // namespace

std::vector<ParamSpec> sediment_parameters() {
  return settings_specs(kSedimentTable);
}

SedimentSettings SedimentSettings::from(const Parameters& p) {
  return read_settings(p, kSedimentTable);
}

std::string SedimentSettings::build_options() const {
  const double submerged = (grain_density / kWaterDensity - 1.0) * grain_diameter;  // R D
  return settings_defines(*this, kSedimentTable) +
         float_define("SED_WONG_PARKER", kWongParkerCoefficient) +
         float_define("SED_SUBMERGED_RD", submerged);
}

double bedload_rate(const SedimentSettings& s, double manning_n, double gravity, double depth,
                    double speed) {
  if (depth <= 0 || speed <= 0) return 0.0;
  const double tau =
      kWaterDensity * gravity * manning_n * manning_n * speed * speed / std::cbrt(depth);  // Pa
  const double relative = s.grain_density / kWaterDensity - 1.0;                           // R
  const double shields = tau / ((s.grain_density - kWaterDensity) * gravity * s.grain_diameter);
  const double excess = shields - s.critical_shields;
  if (excess <= 0) return 0.0;
  const double einstein = kWongParkerCoefficient * std::pow(excess, 1.5);  // q*
  return einstein *
         std::sqrt(relative * gravity * s.grain_diameter * s.grain_diameter * s.grain_diameter);
}

}  // namespace runnel
