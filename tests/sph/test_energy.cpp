// SPDX-License-Identifier: MIT
// Energy at the boundary: a block of water that has settled in a tank with a terrain floor only
// ever loses mechanical energy (kinetic + gravitational + elastic); with the incompressible solver
// it loses energy over a second. With the density integrated a
// half step behind the positions, or a wall force without its continuity partner, such a block
// gains energy every oscillation until it boils over.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "runnel/models/parameter_table.hpp"
#include "runnel/sph/sph_solver.hpp"
#include "runnel/validation/tank.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

struct Energy {
  double total = 0;      // J
  double round_off = 0;  // J: what one float ulp of every particle's y, |v| and ρ is worth
};

// E = Σ m (½|v|² + g y + e(ρ)), e(ρ) = ∫_ρ0^ρ p/ρ'² dρ' the Tait EOS's elastic energy (0 below
// ρ0, where the pressure is clamped). The kinetic part uses v(n−½)·v(n+½) = |v|² − |a|²dt²/4, the
// leapfrog's own kinetic energy, which it conserves exactly for a harmonic oscillator.
Energy mechanical_energy(SphSolver& solver) {
  const SphSettings& s = solver.settings();
  const HostParticles p = solver.particles().download();
  const auto ax = solver.particles().read_field(kAx), ay = solver.particles().read_field(kAy),
             az = solver.particles().read_field(kAz);
  const double m = s.mass(), b = s.tait_b(), r0 = s.rho0, dt = solver.dt();
  Energy e;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double v2 = double(p.f[kVx][i]) * p.f[kVx][i] + double(p.f[kVy][i]) * p.f[kVy][i] +
                      double(p.f[kVz][i]) * p.f[kVz][i];
    const double a2 = double(ax[i]) * ax[i] + double(ay[i]) * ay[i] + double(az[i]) * az[i];
    const double rho = p.f[kRho][i], y = p.f[kY][i];
    double elastic = 0, pressure = 0;
    if (rho > r0) {
      elastic = b * ((std::pow(rho, 6) / std::pow(r0, 7) - 1 / r0) / 6 + 1 / rho - 1 / r0);
      pressure = b * (std::pow(rho / r0, 7) - 1);
    }
    e.total += m * (0.5 * (v2 - 0.25 * a2 * dt * dt) + s.gravity * y + elastic);
    const double ulp = 1.2e-7;  // relative spacing of floats
    e.round_off +=
        m * ulp * (s.gravity * std::fabs(y) + v2 + pressure / (rho * rho) * std::fabs(rho));
  }
  return e;
}

TEST(SphEnergy, SettledBlockInATankOnlyLosesEnergy) {
  Parameters params = default_parameters();
  params.set("sph.walls", true);
  const double height = 0.2, dx = height / 8, width = 8 * dx;
  const SphSettings s = SphSettings::from(params, dx, std::sqrt(9.81 * height));
  SphSolver solver(compute(), s, flat_floor(16, 16, 0.5 * dx), 2 * height);
  solver.add(uniform_block(s, width, height, width));
  while (solver.time() < 1.0) solver.step();  // settles from the uniform start

  const Energy start = mechanical_energy(solver);
  double previous = start.total, worst_gain = 0, worst_bound = start.round_off;
  long long steps = 0;
  while (solver.time() < 2.0) {
    solver.step();
    const Energy e = mechanical_energy(solver);
    if (e.total - previous > worst_gain) worst_gain = e.total - previous, worst_bound = e.round_off;
    previous = e.total;
    ++steps;
  }
  EXPECT_GT(steps, 1000);
  EXPECT_LT(previous, start.total) << "energy must be dissipated";
  // At the default CFL a step's largest gain is about twice the round-off of the float state
  // (docs/sph.md: measured 3.2e-6 J against 1.8e-6 J); a boundary that pumps gains orders more.
  EXPECT_LT(worst_gain, 10.0 * worst_bound) << "worst gain " << worst_gain << " J, round-off "
                                            << worst_bound << " J, E " << start.total << " J";
}

}  // namespace
}  // namespace runnel

namespace runnel {
namespace {

using test::incompressible_energy;

// The incompressible solver's settled block loses energy over a second, but not in every step:
// the solves stop at a tolerance, and what they leave acts as small pressure impulses (measured:
// about half the steps gain, the worst by 0.4 % of the block's energy above its resting level;
// printed, and in docs/validation.md). Its energy must still fall over the second.
TEST(SphEnergy, IncompressibleSettledBlockLosesEnergyOverASecond) {
  Parameters params = default_parameters();
  params.set("sph.walls", true);
  params.set("sph.solver", std::string("dfsph"));
  const double height = 0.2, dx = height / 8, width = 8 * dx;
  const SphSettings s = SphSettings::from(params, dx, std::sqrt(9.81 * height));
  SphSolver solver(compute(), s, flat_floor(16, 16, 0.5 * dx), 2 * height);
  solver.add(uniform_block(s, width, height, width));
  while (solver.time() < 1.0) solver.step();
  const double start = incompressible_energy(solver);
  double previous = start, worst_gain = 0, kinetic_end = 0;
  long long steps = 0, gains = 0;
  while (solver.time() < 2.0) {
    solver.step();
    const double e = incompressible_energy(solver);
    worst_gain = std::max(worst_gain, e - previous);
    gains += e > previous;
    previous = e;
    ++steps;
  }
  const HostParticles p = solver.particles().download();
  for (std::size_t i = 0; i < p.size(); ++i)
    kinetic_end += 0.5 * s.mass() *
                   (double(p.f[kVx][i]) * p.f[kVx][i] + double(p.f[kVy][i]) * p.f[kVy][i] +
                    double(p.f[kVz][i]) * p.f[kVz][i]);
  std::printf(
      "measured: %lld steps, %lld gained energy, the worst by %g J; E %g -> %g J, kinetic "
      "energy at the end %g J\n",
      steps, gains, worst_gain, start, previous, kinetic_end);
  EXPECT_GT(steps, 50);
  EXPECT_LT(previous, start) << "energy must be dissipated";
}

}  // namespace
}  // namespace runnel
