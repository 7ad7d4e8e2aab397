// SPDX-License-Identifier: MIT
#pragma once
#include <string>

#include "runnel/core/parameters.hpp"

namespace runnel {

// The bed's grains (sediment.*, shared by every model with a bed-load law) and the bed-load law:
// Meyer-Peter & Müller (1948) as corrected by Wong & Parker (2006), q* = 3.97 (θ − θc)^(3/2),
// from the Shields stress θ = τ / ((ρs − ρ) g D) of the bed shear the model computes with Manning's
// law, τ = ρ g n² |v|² / d^(1/3). The bed follows the Exner equation (1 − p) ∂z/∂t = −∇·q.
struct SedimentSettings {
  double grain_diameter;     // D, m
  double grain_density;      // ρs, kg/m³
  double porosity;           // p of the bed
  double critical_shields;   // θc
  double adaptation_length;  // m: SPH's bed load relaxes to the flow's over this distance
  static SedimentSettings from(const Parameters& params);
  std::string build_options() const;  // the -D defines the bed-load kernels read
};

inline constexpr double kWaterDensity = 1000.0;  // ρ, kg/m³
inline constexpr double kWongParkerCoefficient = 3.97;

// The volumetric bed-load rate (m² of grains per s, per metre of width) of water `depth` m deep
// flowing at `speed` m/s over a bed of Manning's `manning_n`: the C++ reference of the kernels.
double bedload_rate(const SedimentSettings& s, double manning_n, double gravity, double depth,
                    double speed);

}  // namespace runnel
