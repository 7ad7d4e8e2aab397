// SPDX-License-Identifier: MIT
// The dam break as another code solves it (validation.hpp, dambreak_instant_release): PySPH's own
// example at 67 particles across L, at Koshizuka & Oka's measured times. The same values as
// data/reference/dambreak_pysph_instant_release.csv (a test keeps the two equal), whose header says
// how they were produced.
#include "runnel/validation/validation.hpp"

namespace runnel {

const FrontReading& dambreak_instant_release() {
  static const FrontReading reading{
      "pysph_instant_release",
      "PySPH 1.0b2 dam_break_2d (2-D WCSPH), instant release, 67 particles across L",
      {{0.28825, 1.0978},
       {0.59729, 1.3822},
       {0.83421, 1.6784},
       {1.00899, 1.9332},
       {1.15279, 2.1613},
       {1.29653, 2.4039},
       {1.39877, 2.5838},
       {1.55289, 2.8656},
       {1.63448, 3.0200},
       {1.76846, 3.2805}}};
  return reading;
}

}  // namespace runnel
