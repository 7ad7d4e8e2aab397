// SPDX-License-Identifier: MIT
// Lone droplets on the terrain (physics.md §3, §5): the cases that show whether the terrain
// boundary and the time integration are honest for the smallest flow there is, one particle.
//   bounce   released at rest 2 m above flat ground, for 10 s at each CFL factor: with e = 0 it
//            never rises again, with e = 1 it never rises above its release height (no energy
//            gained at the boundary), with e = 0.5 its first rebound reaches e² of the fall.
//   slide    on a frictionless 20° plane, s(t) fitted by s0 + v0 t + a t²/2: a = g sin α; with
//            Manning's n, the speed follows du/dt = g sin α − g n² u² / D^(4/3) (integrated with
//            RK4; D the water depth of a lone particle, its volume counted on the terrain's
//            vertices).
//   rest     spawned 0.5, 1, 2 and 4 dx above flat ground: the clearance it comes to rest at
//            does not depend on where it was spawned.
// Every figure is measured against its analytic value; no case starts from its answer.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "runnel/sph/footprint.hpp"
#include "runnel/sph/sph_solver.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/surface.hpp"
#include "runnel/validation/tank.hpp"
#include "runnel/validation/validation.hpp"

namespace runnel {
namespace {

constexpr double kSpacing = 0.5;  // m: dx of the droplet, h = 1.2 dx
constexpr double kSlopeDeg = 20.0;

SphSettings droplet_settings(const Parameters& base, double cfl, double restitution,
                             double manning_n, double reference_speed) {
  Parameters p = base;
  p.set("sph.cfl", cfl, "validate");
  // dfsph's flow CFL in the same proportion to its default (0.4) as cfl to wcsph's (0.25).
  p.set("sph.cfl_flow", cfl * 0.4 / 0.25, "validate");
  p.set("sph.restitution", restitution, "validate");
  if (!base.was_set("sph.manning_n")) p.set("sph.manning_n", manning_n, "validate");
  return SphSettings::from(p, kSpacing, reference_speed);
}

HostParticles one_particle(double x, double y, double z) {
  HostParticles p;
  p.push(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z), 0, 0, 0, 1000.0f,
         1e30f);
  p.f[kRho][0] = 1000.0f;
  return p;
}

struct Sample {
  double t, x, y, z, vx, vy, vz;
};

Sample sample(SphSolver& solver) {
  const HostParticles p = solver.particles().download();
  return {solver.time(), p.f[kX][0], p.f[kY][0], p.f[kZ][0], p.f[kVx][0], p.f[kVy][0], p.f[kVz][0]};
}

// The droplet's rest density is the run's ρ0, whatever it is set to.
void set_rest_density(HostParticles& p, const SphSettings& s) {
  for (float& rho : p.f[kRho]) rho = static_cast<float>(s.rho0);
}

}  // namespace

BounceResult droplet_bounce(ComputeContext& compute, const Parameters& params, double cfl,
                            double restitution) {
  const double release = 2.0, duration = 10.0;  // m above the ground, s
  const SphSettings s = droplet_settings(params, cfl, restitution, 0.0,
                                         std::sqrt(2.0 * params.real("sph.gravity") * release));
  const Heightmap ground = flat_floor(8, 8, 1.0);
  SphSolver solver(compute, s, ground, release + 2.0);
  HostParticles p = one_particle(4.0, release, 4.0);
  set_rest_density(p, s);
  solver.add(p);
  BounceResult r;
  r.cfl = cfl;
  r.restitution = restitution;
  r.release_height = release;
  r.contact_height = s.contact_radius;
  bool landed = false, rising = false;
  double previous_y = release;
  while (solver.time() < duration) {
    solver.step();
    const double y = solver.particles().read_field(kY)[0];
    if (!landed && solver.counters().collisions > 0) landed = true;  // its first arrival
    if (landed) {
      r.highest_after_landing = std::max(r.highest_after_landing, y);
      if (y > previous_y) rising = true;
      if (rising && y < previous_y && r.first_rebound < 0) r.first_rebound = previous_y;
    }
    previous_y = y;
  }
  r.steps = static_cast<long long>(solver.steps());
  if (r.first_rebound < 0) r.first_rebound = r.highest_after_landing;
  return r;
}

SlideResult droplet_slide(ComputeContext& compute, const Parameters& params, double cfl,
                          double manning_n) {
  const double g = params.real("sph.gravity"), sin_a = std::sin(kSlopeDeg * M_PI / 180.0);
  const double duration = 3.0, length = 60.0;
  // A plane rising towards +x; the droplet starts at rest on it near the top.
  const Heightmap plane = generate_terrain("plane", static_cast<int>(length) + 1, 9, 1.0, 1,
                                           {{"slope", kSlopeDeg}, {"azimuth", 0.0}});
  const SphSettings s =
      droplet_settings(params, cfl, 0.0, manning_n, std::sqrt(2.0 * g * length * sin_a));
  SphSolver solver(compute, s, plane, plane.max_height() + 4.0);
  const double x0 = length - 4.0, z0 = 4.0;
  const double clearance = (s.contact_radius + s.surface_eps) / std::cos(kSlopeDeg * M_PI / 180.0);
  HostParticles p = one_particle(x0, surface_height(plane, x0, z0) + clearance, z0);
  set_rest_density(p, s);
  solver.add(p);
  // Least squares of s(t) = s0 + v0 t + a t²/2 (s along the slope, downhill positive).
  double m[3][3] = {{0}}, rhs[3] = {0};
  while (solver.time() < duration) {
    solver.step();
    const double t = solver.time();
    const double along =
        (x0 - solver.particles().read_field(kX)[0]) / std::cos(kSlopeDeg * M_PI / 180.0);
    const double basis[3] = {1.0, t, 0.5 * t * t};
    for (int a = 0; a < 3; ++a) {
      rhs[a] += basis[a] * along;
      for (int b = 0; b < 3; ++b) m[a][b] += basis[a] * basis[b];
    }
  }
  // Cramer's rule for the 3×3 normal equations: the acceleration is the third unknown.
  auto det3 = [](double a[3][3]) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
           a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  };
  double m2[3][3];
  std::copy(&m[0][0], &m[0][0] + 9, &m2[0][0]);
  for (int a = 0; a < 3; ++a) m2[a][2] = rhs[a];
  SlideResult r;
  r.cfl = cfl;
  r.manning_n = s.manning_n;
  r.slope_deg = kSlopeDeg;
  const Sample q = sample(solver);
  r.steps = static_cast<long long>(solver.steps());
  r.duration = q.t;
  r.acceleration = det3(m2) / det3(m);
  r.expected_acceleration = g * sin_a;
  r.speed = std::sqrt(q.vx * q.vx + q.vy * q.vy + q.vz * q.vz);
  if (s.manning_n > 0) {
    // du/dt = g sin α − g n² u² / D(s)^(4/3) for a lone particle: its water depth D is its volume
    // counted on the terrain's vertices (water_depth.cl), which varies a little with its position
    // between them. Integrated with RK4 along the slope, 1000 steps a second.
    const double cos_a = std::cos(kSlopeDeg * M_PI / 180.0), radius = footprint_radius(s, 1.0);
    auto accel = [&](double along, double u) {
      const double depth = lone_particle_depth(s.mass() / s.rho0, x0 - along * cos_a, z0, plane.nx,
                                               plane.ny, plane.cell, radius);
      return g * sin_a - g * s.manning_n * s.manning_n * u * u / std::pow(depth, 4.0 / 3.0);
    };
    double along = 0, u = 0;
    const double h = 1e-3;
    for (double t = 0; t < q.t - 0.5 * h; t += h) {
      const double k1u = accel(along, u), k1s = u;
      const double k2u = accel(along + 0.5 * h * k1s, u + 0.5 * h * k1u), k2s = u + 0.5 * h * k1u;
      const double k3u = accel(along + 0.5 * h * k2s, u + 0.5 * h * k2u), k3s = u + 0.5 * h * k2u;
      const double k4u = accel(along + h * k3s, u + h * k3u), k4s = u + h * k3u;
      u += h / 6 * (k1u + 2 * k2u + 2 * k3u + k4u);
      along += h / 6 * (k1s + 2 * k2s + 2 * k3s + k4s);
    }
    r.expected_speed = u;
  } else {
    r.expected_speed = g * sin_a * q.t;
  }
  return r;
}

double droplet_rest_clearance(ComputeContext& compute, const Parameters& params,
                              double spawn_height) {
  const SphSettings s = droplet_settings(
      params, params.real("sph.cfl"), params.real("sph.restitution"), params.real("sph.manning_n"),
      std::sqrt(2.0 * params.real("sph.gravity") * 2.0));
  const Heightmap ground = flat_floor(8, 8, 1.0);
  SphSolver solver(compute, s, ground, 4.0);
  HostParticles p = one_particle(4.0, spawn_height, 4.0);
  set_rest_density(p, s);
  solver.add(p);
  while (solver.time() < 2.0) solver.step();
  return sample(solver).y;  // the ground is flat at height 0: the clearance along the normal
}

ValidationResult validate_droplet(ComputeContext& compute, const ValidationOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  ValidationResult r;
  r.name = "droplet";
  r.particles = 1;
  std::vector<JsonObject> bounces, slides, rests;
  double worst = 0, worst_target = 0.01;
  auto consider = [&](double error, double target) {
    if (error / target > worst / worst_target) worst = error, worst_target = target;
    return error <= target;
  };
  for (double cfl : {0.1, 0.25, 0.5}) {
    for (double e : {0.0, 0.5, 1.0}) {
      const BounceResult b = droplet_bounce(compute, options.params, cfl, e);
      r.steps += b.steps;
      // No energy gained: never above the release height (1 % allowed); e² of the fall on the
      // first rebound (2 %).
      const double gain = std::max(0.0, b.highest_after_landing / b.release_height - 1.0);
      const double fall = b.release_height - b.contact_height;
      const double rebound_error =
          std::fabs((b.first_rebound - b.contact_height) - e * e * fall) / fall;
      // Both are considered (each records its worst case), then both must pass.
      const bool gain_ok = consider(gain, 0.01), rebound_ok = consider(rebound_error, 0.02);
      const bool ok = gain_ok && rebound_ok;
      bounces.push_back(JsonObject()
                            .add("cfl", cfl)
                            .add("restitution", e)
                            .add("release_height_m", b.release_height)
                            .add("highest_after_landing_m", b.highest_after_landing)
                            .add("first_rebound_m", b.first_rebound)
                            .add("expected_rebound_m", b.contact_height + e * e * fall)
                            .add("height_gain", gain)
                            .add("rebound_error", rebound_error)
                            .add("passed", ok));
    }
    for (double n : {0.0, 0.03}) {
      const SlideResult sl = droplet_slide(compute, options.params, cfl, n);
      r.steps += sl.steps;
      const double accel_error =
          n == 0 ? std::fabs(sl.acceleration / sl.expected_acceleration - 1.0) : 0.0;
      const double speed_error = std::fabs(sl.speed / sl.expected_speed - 1.0);
      const bool accel_ok = consider(accel_error, 0.02), speed_ok = consider(speed_error, 0.02);
      const bool ok = accel_ok && speed_ok;
      slides.push_back(JsonObject()
                           .add("cfl", cfl)
                           .add("manning_n", sl.manning_n)
                           .add("slope_deg", sl.slope_deg)
                           .add("duration_s", sl.duration)
                           .add("acceleration", sl.acceleration)
                           .add("g_sin_alpha", sl.expected_acceleration)
                           .add("acceleration_error", accel_error)
                           .add("speed", sl.speed)
                           .add("expected_speed", sl.expected_speed)
                           .add("speed_error", speed_error)
                           .add("passed", ok));
    }
  }
  std::vector<double> clearances;
  for (double spawn : {0.5, 1.0, 2.0, 4.0}) {
    const double c = droplet_rest_clearance(compute, options.params, spawn * kSpacing);
    clearances.push_back(c);
    rests.push_back(JsonObject()
                        .add("spawn_height_dx", spawn)
                        .add("clearance_m", c)
                        .add("clearance_dx", c / kSpacing));
  }
  const auto [lo, hi] = std::minmax_element(clearances.begin(), clearances.end());
  const double spread = (*hi - *lo) / (0.5 * (*hi + *lo));
  consider(spread, 0.05);
  r.relative_error = worst;
  r.target = worst_target;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.details.add("spacing_m", kSpacing)
      .add("bounce", bounces)
      .add("slide", slides)
      .add("rest", rests)
      .add("rest_clearance_spread", spread)
      .add("rest_clearance_target", 0.05);
  return r;
}

}  // namespace runnel
