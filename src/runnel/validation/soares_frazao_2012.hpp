// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <vector>

namespace runnel {

// The IAHR benchmark "dam-break flow over a mobile bed" (Soares-Frazão et al. 2012, J. Hydraulic
// Research 50(4):364–375): what was measured, as data/reference/soares_frazao_2012/ holds it.
// Coordinates in metres: x from the gate's centre (downstream positive), y from the flume's axis;
// elevations above the fixed floor.

// A gauge's water surface, one reading a second.
struct MobileBedGauge {
  std::string name;
  double x, y;
  std::vector<double> t, surface;
};
const std::vector<MobileBedGauge>& soares_frazao_gauges();

// The final bed along a line y = const, one series per repeat of the experiment.
struct MobileBedProfile {
  std::string name;
  double y;
  struct Repeat {
    std::vector<double> x, z;
  };
  std::vector<Repeat> repeats;
};
const std::vector<MobileBedProfile>& soares_frazao_profiles();

}  // namespace runnel
