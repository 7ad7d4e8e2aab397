// SPDX-License-Identifier: MIT
#include "runnel/sph/sph_reference.hpp"

#include <cmath>

namespace runnel::sph_reference {

namespace {
double alpha(double h) {
  return 21.0 / (16.0 * M_PI * h * h * h);
}
}  // namespace

double wendland_w(double r, double h) {
  const double q = r / h;
  if (q >= 2.0) return 0.0;
  return alpha(h) * std::pow(1.0 - 0.5 * q, 4) * (2.0 * q + 1.0);
}

double wendland_grad_factor(double r, double h) {
  const double q = r / h;
  if (q >= 2.0) return 0.0;
  return -5.0 * alpha(h) / (h * h) * std::pow(1.0 - 0.5 * q, 3);
}

double wall_integral(double d, double h) {
  const double q = std::max(d, 0.0) / h;
  if (q >= 2.0) return 0.0;
  const double a = q * q / 2 - 5 * std::pow(q, 4) / 8 + std::pow(q, 5) / 2 -
                   5 * std::pow(q, 6) / 32 + std::pow(q, 7) / 56;
  return 2.0 * M_PI * alpha(h) * h * h * (2.0 / 7.0 - a);
}

double wall_moment_normal(double d, double h) {
  const double q = std::max(d, 0.0) / h;
  if (q >= 2.0) return 0.0;
  return 0.5 - 7 * std::pow(q, 3) / 8 + 21 * std::pow(q, 5) / 16 - 35 * std::pow(q, 6) / 32 +
         45 * std::pow(q, 7) / 128 - 21 * std::pow(q, 8) / 512;
}

double wall_moment_tangent(double d, double h) {
  const double q = std::max(d, 0.0) / h;
  if (q >= 2.0) return 0.0;
  return 0.5 - 3 * q / 4 + 7 * std::pow(q, 3) / 16 - 21 * std::pow(q, 5) / 64 +
         7 * std::pow(q, 6) / 32 - 15 * std::pow(q, 7) / 256 + 3 * std::pow(q, 8) / 512;
}

Rates interaction_rates(const HostParticles& p, const SphSettings& s) {
  const std::size_t n = p.size();
  Rates r{std::vector<double>(n, 0.0), std::vector<double>(n, -s.gravity),
          std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)};
  const double h = s.h, m = s.mass(), eta2 = 0.01 * h * h, b = s.tait_b();
  const double hydrostatic = s.rho0 * s.gravity / (s.c0 * s.c0);
  auto pressure = [&](double rho) {
    const double pr = b * (std::pow(rho / s.rho0, 7) - 1.0);
    return s.clamp_negative_pressure ? std::max(pr, 0.0) : pr;
  };
  for (std::size_t i = 0; i < n; ++i) {
    const double rhoi = p.f[kRho][i], pi = pressure(rhoi);
    for (std::size_t j = 0; j < n; ++j) {
      if (i == j) continue;
      const double x[3] = {double(p.f[kX][i]) - p.f[kX][j], double(p.f[kY][i]) - p.f[kY][j],
                           double(p.f[kZ][i]) - p.f[kZ][j]};
      const double r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
      if (r2 >= 4 * h * h) continue;
      const double f = wendland_grad_factor(std::sqrt(r2), h);
      const double v[3] = {double(p.f[kVx][i]) - p.f[kVx][j], double(p.f[kVy][i]) - p.f[kVy][j],
                           double(p.f[kVz][i]) - p.f[kVz][j]};
      const double vdotx = v[0] * x[0] + v[1] * x[1] + v[2] * x[2];
      const double rhoj = p.f[kRho][j], pj = pressure(rhoj);
      const double rho_dynamic = (rhoi - rhoj) + hydrostatic * x[1];
      r.drho[i] +=
          m * vdotx * f + 2 * s.delta * h * s.c0 * (m / rhoj) * rho_dynamic * r2 * f / (r2 + eta2);
      const double visc =
          vdotx < 0 ? -s.alpha_visc * s.c0 * (h * vdotx / (r2 + eta2)) / (0.5 * (rhoi + rhoj))
                    : 0.0;
      const double k = -m * (pi / (rhoi * rhoi) + pj / (rhoj * rhoj) + visc) * f;
      r.ax[i] += k * x[0];
      r.ay[i] += k * x[1];
      r.az[i] += k * x[2];
    }
  }
  return r;
}

}  // namespace runnel::sph_reference
