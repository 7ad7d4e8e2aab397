// SPDX-License-Identifier: MIT
// The SPH smoothing kernel (physics.md §2): Wendland C2 in 3-D, support 2h, q = r/h.
//   W(q)      = α (1 − q/2)^4 (2q + 1),        α = 21 / (16 π h³)
//   ∇_i W_ij  = −(5α/h²) (1 − q/2)^3 x_ij       (returned as the factor F with ∇_i W = F x_ij)
// and the integral a planar wall uses in place of its missing particles:
//   G(d) = 2π ∫_d^{2h} W(r) r dr = 2π α h² [A(2) − A(d/h)],
//   A(q) = q²/2 − 5q⁴/8 + q⁵/2 − 5q⁶/32 + q⁷/56,  A(2) = 2/7.
// For a pressure field that grows linearly into the wall (the hydrostatic state), the missing
// particles also contribute M(d)·∇p, with M(d) = ∫_{beyond the wall} |F| Δ⊗Δ dV = a(q) n⊗n + b(q)(I − n⊗n):
//   a(q) = 1/2 − 7q³/8 + 21q⁵/16 − 35q⁶/32 + 45q⁷/128 − 21q⁸/512
//   b(q) = 1/2 − 3q/4 + 7q³/16 − 21q⁵/64 + 7q⁶/32 − 15q⁷/256 + 3q⁸/512
// (both 1/2 at the wall, 0 at q = 2; over the whole space M = I).
// Compile-time constants (host -D): SPH_H (m).

#define SPH_ALPHA_W (21.0f / (16.0f * M_PI_F * SPH_H * SPH_H * SPH_H))

// Both are branch-free (t clamped at 0 beyond the support) so that neighbour loops vectorise.
inline float wendland_w(float r) {
  const float q = r * (1.0f / SPH_H);
  const float t = max(1.0f - 0.5f * q, 0.0f);
  const float t2 = t * t;
  return SPH_ALPHA_W * t2 * t2 * (2.0f * q + 1.0f);
}

// F(r) such that ∇_i W_ij = F · (x_i − x_j); zero outside the support.
inline float wendland_grad_factor(float r) {
  const float q = r * (1.0f / SPH_H);
  const float t = max(1.0f - 0.5f * q, 0.0f);
  return -(5.0f * SPH_ALPHA_W / (SPH_H * SPH_H)) * t * t * t;
}

inline float wall_integral(float d) {
  float q = max(d, 0.0f) * (1.0f / SPH_H);
  if (q >= 2.0f) return 0.0f;
  const float q2 = q * q;
  const float a = q2 * (0.5f + q2 * (-0.625f + q * (0.5f + q * (-0.15625f + q * (1.0f / 56.0f)))));
  return 2.0f * M_PI_F * SPH_ALPHA_W * SPH_H * SPH_H * (2.0f / 7.0f - a);
}

// a(q) of the wall moment tensor (dimensionless), q = d/h.
inline float wall_moment_normal(float d) {
  const float q = max(d, 0.0f) * (1.0f / SPH_H);
  if (q >= 2.0f) return 0.0f;
  const float q3 = q * q * q;
  return 0.5f + q3 * (-0.875f + q * q * (1.3125f + q * (-1.09375f + q * (0.3515625f - q * 0.041015625f))));
}

// b(q) of the wall moment tensor (dimensionless), q = d/h.
inline float wall_moment_tangent(float d) {
  const float q = max(d, 0.0f) * (1.0f / SPH_H);
  if (q >= 2.0f) return 0.0f;
  const float q2 = q * q;
  return 0.5f - 0.75f * q + q2 * q * (0.4375f + q2 * (-0.328125f + q * (0.21875f + q * (-0.05859375f + q * 0.005859375f))));
}

// Γ(d) = ∫_{beyond a wall at distance d} W dV = ∫_d^{2h} G(s) ds: the share of the kernel the wall
// removes (1/2 at the wall, 0 from 2h):
//   Γ = (21/8) [A(2)(2 − q) − B(2) + B(q)],  B(q) = q³/6 − q⁵/8 + q⁶/12 − 5q⁷/224 + q⁸/448,
//   B(2) = 8/21.
inline float wall_volume(float d) {
  const float q = max(d, 0.0f) * (1.0f / SPH_H);
  if (q >= 2.0f) return 0.0f;
  const float q2 = q * q;
  const float b = q2 * q * ((1.0f / 6.0f) + q2 * (-0.125f + q * ((1.0f / 12.0f) + q * (-5.0f / 224.0f + q * (1.0f / 448.0f)))));
  return 2.625f * ((2.0f / 7.0f) * (2.0f - q) - (8.0f / 21.0f) + b);
}
