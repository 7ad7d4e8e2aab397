// SPDX-License-Identifier: MIT
#include "runnel/sph/sph_settings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "runnel/compute/build_options.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/parameter_groups.hpp"
#include "runnel/core/settings_table.hpp"
#include "runnel/sph/pressure/registry.hpp"

namespace runnel {

namespace {

// "the pressure solver: NAME, SUMMARY; NAME, SUMMARY", from the registry.
std::string solver_help() {
  std::string help = "the pressure solver: ";
  const auto& methods = pressure_methods();
  for (std::size_t k = 0; k < methods.size(); ++k)
    help += (k > 0 ? "; " : "") + methods[k].name + ", " + methods[k].summary;
  return help;
}

// clang-format off
const SettingsTable<SphSettings> kSphTable = {
      // sph: the SPH fluid (physics.md §2, docs/sph.md)
      {"sph.solver", "\"" + pressure_methods().front().name + "\"", "", 0, 0, pressure_method_names(), solver_help(), &SphSettings::solver},
      {"sph.spacing", "0", "m", 0, 1e4, {}, "particle spacing dx (particle volume dx³); 0: derived from the case (half the terrain's cell size for runs: several particles across a channel)", &SphSettings::spacing},
      {"sph.h_factor", "1.2", "1", 0.8, 2.5, {}, "smoothing length h = h_factor · dx (support radius 2h)", &SphSettings::h_factor},
      {"sph.rho0", "1000", "kg/m^3", 1, 1e5, {}, "rest density ρ0", &SphSettings::rho0, "SPH_RHO0"},
      {"sph.c0", "0", "m/s", 0, 1e5, {}, "speed of sound of wcsph (with dfsph it only scales the viscosity, α c0 h / 10); 0: 10 × the case's reference speed (free fall from the spawn height, or sqrt(g H))", &SphSettings::c0, "SPH_C0"},
      {"sph.alpha_visc", "0.02", "1", 0, 10, {}, "Monaghan artificial viscosity α", &SphSettings::alpha_visc, "SPH_ALPHA_VISC"},
      {"sph.delta", "0.1", "1", 0, 1, {}, "δ-SPH density diffusion coefficient (Molteni & Colagrossi 2009)", &SphSettings::delta, "SPH_DELTA"},
      {"sph.cfl", "0.25", "1", 0.01, 0.5, {}, "wcsph's time step factor: dt = cfl · min(h/(c0 + |v|max), sqrt(h/|a|max))", &SphSettings::cfl},
      {"sph.cfl_flow", "0.4", "1", 0.01, 1, {}, "dfsph's time step factor: dt = cfl_flow · min(dx/|v|max, ½ sqrt(dx/|a|max)), |a| the non-pressure accelerations", &SphSettings::cfl_flow},
      {"sph.dfsph_density_error", "0.05", "%", 1e-4, 10, {}, "dfsph: the constant-density solve iterates until the mean compression of the particles under pressure is below this share of ρ0", &SphSettings::dfsph_density_error},
      {"sph.dfsph_divergence_error", "0.1", "%", 1e-3, 100, {}, "dfsph: the divergence-free solve iterates until the mean rate of compression, over one step, is below this share of ρ0", &SphSettings::dfsph_divergence_error},
      {"sph.dfsph_floor_images", "false", "", 0, 0, {}, "dfsph: the terrain as the mirror images of each particle's neighbours across its tangent plane, their pressure carried on hydrostatically (a symmetric pressure system: the hydrostatic tank's column within 5 %, compression 0.09 %; rain spawned inside water can stop a run, docs/sph.md); false: the terrain's volume map with the particle's own pressure mirrored", &SphSettings::dfsph_floor_images, "DFSPH_FLOOR_IMAGES"},
      {"sph.dfsph_max_iterations", "100", "1", 1, 10000, {}, "dfsph: iterations of each pressure solve at most; a solve that reaches it goes on with the error it has, and the run says so on stderr", &SphSettings::dfsph_max_iterations},
      {"sph.dt_min", "1e-7", "s", 1e-12, 1, {}, "smallest time step: reaching it stops the run as unstable", &SphSettings::dt_min},
      {"sph.dt_max", "0", "s", 0, 10, {}, "largest time step; 0: 0.01 s for wcsph, 0.05 s for dfsph (whose step the flow sets: 0.4 dx/|v|max is 33 ms at 12 m/s on 1 m particles)", &SphSettings::dt_max},
      {"sph.gravity", "9.81", "m/s^2", 0, 100, {}, "gravitational acceleration (along −y)", &SphSettings::gravity, "SPH_GRAVITY"},
      {"sph.clamp_negative_pressure", "true", "", 0, 0, {}, "clamp negative pressure to 0 (free-surface rain: no tensile attraction between droplets)", &SphSettings::clamp_negative_pressure, "SPH_CLAMP_NEGATIVE_PRESSURE"},
      {"sph.walls", "false", "", 0, 0, {}, "vertical walls at the domain edges; false: open edges, particles that leave are removed as outflow", &SphSettings::walls, "SPH_WALLS"},
      {"sph.restitution", "0", "1", 0, 1, {}, "restitution e of the terrain and wall contact", &SphSettings::restitution, "SPH_RESTITUTION"},
      {"sph.manning_n", "0.03", "s/m^(1/3)", 0, 1, {}, "Manning's roughness n of the terrain: bed shear stress ρ g n² |u|²/D^(1/3) on particles touching it (D the local flow depth); 0: frictionless", &SphSettings::manning_n},
      {"sph.contact_radius", "0.5", "dx", 0, 2, {}, "particle radius for the terrain contact: a resting particle's centre sits this far above the terrain along the normal (0.5: the particle of volume dx³ rests on its lowest point)", &SphSettings::contact_radius, "SPH_CONTACT_RADIUS"},
      {"sph.contact_face_normal", "false", "", 0, 0, {}, "the contact also takes away what still moves into the hit triangle's own face after the response along the interpolated normal (at bends the interpolated normal alone leaves a velocity into the face, which the contact stops again every step: docs/sph.md, \"The contact at bends\")", &SphSettings::contact_face_normal, "SPH_CONTACT_FACE_NORMAL"},
      {"sph.surface_eps", "0.01", "dx", 0, 0.5, {}, "ε, how far above the contact surface a particle is put after a hit", &SphSettings::surface_eps, "SPH_SURFACE_EPS"},
      {"sph.density_min", "0.1", "1", 0.001, 1, {}, "density floor as a fraction of ρ0: the continuity equation lets a particle of a thinning film or of spray expand without bound (pressure is clamped at zero below ρ0, so nothing pulls it back); its density is held here. A particle added below it stops the run", &SphSettings::density_min},
      {"sph.density_max", "1.5", "1", 1, 100, {}, "largest sane density as a fraction of ρ0: above it the run stops", &SphSettings::density_max},
};
// clang-format on

}  // namespace

std::vector<ParamSpec> sph_parameters() {
  return settings_specs(kSphTable);
}

SphSettings SphSettings::from(const Parameters& p, double default_spacing, double reference_speed) {
  SphSettings s = read_settings(p, kSphTable);
  // The automatic values and those given in multiples of dx, resolved in place.
  if (!(s.spacing > 0)) s.spacing = default_spacing;
  if (!(s.spacing > 0)) throw input_error("sph.spacing: must be positive");
  s.h = s.h_factor * s.spacing;
  if (!(s.c0 > 0)) s.c0 = 10.0 * reference_speed;
  if (!(s.c0 > 0))
    throw input_error("sph.c0: must be positive (no reference speed to derive it from)");
  if (!(s.dt_max > 0)) s.dt_max = pressure_method(s.solver).default_dt_max;
  if (s.dt_min >= s.dt_max) throw input_error("sph.dt_min: must be smaller than sph.dt_max");
  if (!(s.density_min < 1.0 && s.density_max > 1.0)) {
    throw input_error(
        "sph.density_min, sph.density_max: the sane range must contain the rest "
        "density (density_min below 1, density_max above 1)");
  }
  s.contact_radius *= s.spacing;
  s.surface_eps *= s.spacing;
  return s;
}

double particle_spacing(const Parameters& params, double terrain_cell) {
  return params.real("sph.spacing") > 0 ? params.real("sph.spacing") : 0.5 * terrain_cell;
}

bool SphSettings::incompressible() const {
  return pressure_method(solver).incompressible;
}

double footprint_radius(const SphSettings& s, double terrain_cell) {
  return std::min(std::max(2.0 * s.h, 2.0 * terrain_cell), 8.0 * terrain_cell);
}

double SphSettings::lattice_sum() const {
  // Σ_j dx³ W(|x_j|) over a cubic lattice of spacing dx (the particle itself included), in
  // double precision, with W the Wendland C2 kernel of cl/sph_kernel.cl.
  const double alpha = 21.0 / (16.0 * 3.14159265358979323846 * h * h * h);
  const int reach = static_cast<int>(std::ceil(2.0 * h / spacing));
  double sum = 0.0;
  for (int i = -reach; i <= reach; ++i)
    for (int j = -reach; j <= reach; ++j)
      for (int k = -reach; k <= reach; ++k) {
        const double q = spacing * std::sqrt(double(i * i + j * j + k * k)) / h;
        if (q >= 2.0) continue;
        const double t = 1.0 - 0.5 * q;
        sum += alpha * t * t * t * t * (2.0 * q + 1.0);
      }
  return sum * spacing * spacing * spacing;
}

std::string SphSettings::build_options() const {
  std::string o = settings_defines(*this, kSphTable);
  o += float_define("SPH_H", h);
  o += float_define("SPH_MASS", mass());
  o += float_define("SPH_B", tait_b());
  o += float_define("SPH_MANNING_G_N2", gravity * manning_n * manning_n);
  o += float_define("SPH_RHO_FLOOR", density_min * rho0);
  o += float_define("DFSPH_VOLUME", spacing * spacing * spacing / lattice_sum());
  return o;
}

}  // namespace runnel
