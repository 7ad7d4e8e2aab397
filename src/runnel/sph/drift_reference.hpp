// SPDX-License-Identifier: MIT
#pragma once
#include <array>

#include "runnel/sph/sph_settings.hpp"

namespace runnel::drift_reference {

using Vec = std::array<double, 3>;

// A terrain that is one plane, y = y0 + slope_x·x + slope_z·z, over [0, lx] × [0, lz] (open
// edges). On a plane the contact surface is the same plane raised by r / n_y.
struct Plane {
  double y0, slope_x, slope_z, lx, lz;
};

struct Particle {
  Vec x, v;      // m, m/s: position and velocity at the start of the step
  Vec a;         // m/s², the last force pass's acceleration
  double depth;  // m, the water depth on the bed (water_depth.cl)
};

struct Drifted {
  Vec x, v;
  bool touching = false;
  bool outflow = false;
};

// The drift of cl/integrate.cl (the opening half kick v += a·dt/2, x + v·dt, outflow, the first
// crossing of the contact surface with the time-accurate rebound, the end-of-step projection,
// Manning bed friction) for one particle over a plane, in plain C++ and double precision: the
// oracle of the drift kernel.
Drifted drift(const Particle& p, const Plane& plane, const SphSettings& s, double dt);

}  // namespace runnel::drift_reference
