// SPDX-License-Identifier: MIT
#pragma once

namespace runnel {

// Rain as people give it (an intensity in mm/h) and as the models use it (a depth of water per
// second, m/s): the one conversion, so every model, the viewer's brush and the session logs agree
// to the bit.
inline double rain_depth_rate(double intensity_mm_per_h) {
  return intensity_mm_per_h / 1000.0 / 3600.0;
}
inline double rain_intensity(double depth_rate_m_per_s) {
  return depth_rate_m_per_s * 1000.0 * 3600.0;
}

}  // namespace runnel
