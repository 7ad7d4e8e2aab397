// SPDX-License-Identifier: MIT
#pragma once

namespace runnel {

// The kinematic wave for rain on a plane (Woolhiser & Liggett 1967; Singh 1996, "Kinematic Wave
// Modeling in Water Resources"): water running off a plane of length L (m, from the divide at x = 0
// to the open foot at x = L), slope S and Manning roughness n under rain i (m/s) that falls from
// t = 0 until t = D, with Manning's law as the only momentum balance:
//   ∂h/∂t + ∂q/∂x = i (while it rains),   q = α h^m,   α = √S / n,   m = 5/3,
// h the depth (m), q the discharge per unit width (m²/s). The characteristics carry the depth at
// the speed c = α m h^(m−1). Valid where the kinematic number k = S L / (h_L F²) = L g n² /
// h_L^(4/3) is at least 10 (h_L, F the depth and Froude number at the foot at equilibrium).
//
// Every function here is the closed form or, for the recession, the characteristic solved for the
// depth by bisection: the reference that the models' overland flow is scored against, computed
// from the parameters alone.
struct KinematicPlane {
  double length = 0;     // L, m
  double slope = 0;      // S, m/m
  double manning_n = 0;  // n, s/m^(1/3)
  double rain = 0;       // i, m/s
  double duration = 0;   // D, s: the rain stops then; D ≥ equilibrium_time() (a full equilibrium)

  double alpha() const;  // √S / n
  // t_e = (n L / (√S i^(2/3)))^(3/5): when the characteristic from the divide reaches the foot.
  double equilibrium_time() const;
  // The steady depth h(x) = (i x / α)^(3/5).
  double equilibrium_depth(double x) const;
  // The water stored per unit width at equilibrium, ∫₀ᴸ h dx = (5/8) L h(L).
  double equilibrium_storage() const;
  // k = L g n² / h_L^(4/3) at equilibrium; the kinematic wave is exact as k → ∞ and good from 10.
  double kinematic_number(double gravity = 9.81) const;

  // The depth at x (0 ≤ x ≤ L) and time t ≥ 0, and the discharge per unit width there.
  double depth(double x, double t) const;
  double discharge(double x, double t) const;
  // The outflow per unit width at the foot, q(L, t), m²/s: rises as α (i t)^(5/3) until t_e, holds
  // i L until the rain stops, then recedes along the characteristics.
  double outflow(double t) const;
  // The water on the plane per unit width, m²: ∫₀ᴸ h(x, t) dx (closed form while it rains, by
  // quadrature of the characteristics' depths after).
  double storage(double t) const;
};

}  // namespace runnel
