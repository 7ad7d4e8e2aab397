// SPDX-License-Identifier: MIT
#include "runnel/sph/sph_settings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "runnel/compute/build_options.hpp"
#include "runnel/core/error.hpp"

namespace runnel {

SphSettings SphSettings::from(const Parameters& p, double default_spacing, double reference_speed) {
  SphSettings s;
  s.spacing = p.real("sph.spacing") > 0 ? p.real("sph.spacing") : default_spacing;
  if (!(s.spacing > 0)) throw input_error("sph.spacing: must be positive");
  s.h = p.real("sph.h_factor") * s.spacing;
  s.rho0 = p.real("sph.rho0");
  s.c0 = p.real("sph.c0") > 0 ? p.real("sph.c0") : 10.0 * reference_speed;
  if (!(s.c0 > 0))
    throw input_error("sph.c0: must be positive (no reference speed to derive it from)");
  s.alpha_visc = p.real("sph.alpha_visc");
  s.delta = p.real("sph.delta");
  s.cfl = p.real("sph.cfl");
  s.dt_min = p.real("sph.dt_min");
  s.dt_max = p.real("sph.dt_max");
  if (s.dt_min >= s.dt_max) throw input_error("sph.dt_min: must be smaller than sph.dt_max");
  s.gravity = p.real("sph.gravity");
  s.restitution = p.real("sph.restitution");
  s.manning_n = p.real("sph.manning_n");
  s.contact_radius = p.real("sph.contact_radius") * s.spacing;
  s.surface_eps = p.real("sph.surface_eps") * s.spacing;
  s.density_min = p.real("sph.density_min");
  s.density_max = p.real("sph.density_max");
  s.clamp_negative_pressure = p.boolean("sph.clamp_negative_pressure");
  s.walls = p.boolean("sph.walls");
  return s;
}

double footprint_radius(const SphSettings& s, double terrain_cell) {
  return std::min(std::max(2.0 * s.h, 2.0 * terrain_cell), 8.0 * terrain_cell);
}

std::string SphSettings::build_options() const {
  std::string o;
  o += float_define("SPH_H", h);
  o += float_define("SPH_MASS", mass());
  o += float_define("SPH_RHO0", rho0);
  o += float_define("SPH_C0", c0);
  o += float_define("SPH_B", tait_b());
  o += float_define("SPH_ALPHA_VISC", alpha_visc);
  o += float_define("SPH_DELTA", delta);
  o += float_define("SPH_GRAVITY", gravity);
  o += float_define("SPH_RESTITUTION", restitution);
  o += float_define("SPH_MANNING_G_N2", gravity * manning_n * manning_n);
  o += float_define("SPH_CONTACT_RADIUS", contact_radius);
  o += float_define("SPH_SURFACE_EPS", surface_eps);
  o += std::string(" -DSPH_CLAMP_NEGATIVE_PRESSURE=") + (clamp_negative_pressure ? "1" : "0");
  o += std::string(" -DSPH_WALLS=") + (walls ? "1" : "0");
  return o;
}

}  // namespace runnel
