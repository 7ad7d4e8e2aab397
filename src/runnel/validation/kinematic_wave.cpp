// SPDX-License-Identifier: MIT
#include "runnel/validation/kinematic_wave.hpp"

#include <algorithm>
#include <cmath>

namespace runnel {
namespace {

constexpr double kM = 5.0 / 3.0;  // Manning: q = α h^(5/3)

// ∫₀ˣ (i s / α)^(3/5) ds = (5/8) x (i x / α)^(3/5).
double steady_storage_to(double x, double rain, double alpha) {
  return 0.625 * x * std::pow(rain * x / alpha, 0.6);
}

// How far the characteristic that left the divide at t = 0 has come while it rains: x = α (i t)^m /
// i.
double front(double t, double rain, double alpha) {
  return alpha * std::pow(rain * t, kM) / rain;
}

}  // namespace

double KinematicPlane::alpha() const {
  return std::sqrt(slope) / manning_n;
}

double KinematicPlane::equilibrium_time() const {
  return std::pow(manning_n * length / (std::sqrt(slope) * std::pow(rain, 2.0 / 3.0)), 0.6);
}

double KinematicPlane::equilibrium_depth(double x) const {
  return std::pow(rain * std::max(x, 0.0) / alpha(), 0.6);
}

double KinematicPlane::equilibrium_storage() const {
  return steady_storage_to(length, rain, alpha());
}

double KinematicPlane::kinematic_number(double gravity) const {
  return length * gravity * manning_n * manning_n / std::pow(equilibrium_depth(length), 4.0 / 3.0);
}

double KinematicPlane::depth(double x, double t) const {
  const double a = alpha();
  x = std::clamp(x, 0.0, length);
  if (t <= duration) {
    // Where the characteristic that left the divide at t = 0 has passed, the depth is steady;
    // ahead of it every characteristic started on the plane at t = 0 and has gathered i t.
    return x <= front(t, rain, a) ? equilibrium_depth(x) : rain * t;
  }
  // Recession (the plane was at equilibrium when the rain stopped): the characteristic through
  // (x, t) left x0 = α h0^m / i at t = D with the steady depth h0 and keeps it, travelling at
  // α m h0^(m−1); where it lands grows with h0, so bisect for the h0 that lands at x.
  const double elapsed = t - duration;
  const auto lands = [&](double h0) {
    return a * std::pow(h0, kM) / rain + a * kM * std::pow(h0, kM - 1) * elapsed;
  };
  double low = 0, high = equilibrium_depth(x);
  for (int k = 0; k < 200 && high - low > 1e-15 * std::max(high, 1e-300); ++k) {
    const double mid = 0.5 * (low + high);
    (lands(mid) < x ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

double KinematicPlane::discharge(double x, double t) const {
  return alpha() * std::pow(depth(x, t), kM);
}

double KinematicPlane::outflow(double t) const {
  return discharge(length, t);
}

double KinematicPlane::storage(double t) const {
  const double a = alpha();
  if (t <= duration) {
    const double reached = std::min(front(t, rain, a), length);
    return steady_storage_to(reached, rain, a) + (length - reached) * rain * t;
  }
  // Simpson's rule in s with x = L s²: the depth's x^(3/5) near the divide becomes smooth in s.
  constexpr int kIntervals = 4000;
  double sum = 0;
  for (int k = 0; k <= kIntervals; ++k) {
    const double s = static_cast<double>(k) / kIntervals;
    const double weight = (k == 0 || k == kIntervals) ? 1 : (k % 2 == 1 ? 4 : 2);
    sum += weight * depth(length * s * s, t) * 2 * length * s;
  }
  return sum / (3.0 * kIntervals);
}

}  // namespace runnel
