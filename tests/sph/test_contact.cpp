// SPDX-License-Identifier: MIT
// A lone droplet on the terrain against its analytic outcomes (physics.md §3, §5): the contact
// never adds energy (no rebound above the release height at any CFL), a rebound reaches e² of the
// fall, a frictionless slide accelerates at g sin α, Manning's bed friction gives its
// terminal-speed law, and the height a droplet rests at does not depend on where it was spawned.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "runnel/models/parameter_table.hpp"
#include "runnel/validation/validation.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

TEST(Contact, LoneDropletNeverRisesAboveItsRelease) {
  for (double cfl : {0.1, 0.25, 0.5}) {
    for (double e : {0.0, 1.0}) {
      const BounceResult b = droplet_bounce(compute(), default_parameters(), cfl, e);
      EXPECT_LE(b.highest_after_landing, 1.01 * b.release_height) << "cfl " << cfl << ", e " << e;
      if (e == 1.0) {  // elastic: it comes back up to where it started, again and again
        EXPECT_GE(b.highest_after_landing, 0.99 * b.release_height) << "cfl " << cfl;
      } else {  // plastic: it stays on the ground, its lowest point touching it
        EXPECT_NEAR(b.highest_after_landing, b.contact_height, 0.02 * b.contact_height)
            << "cfl " << cfl;
      }
    }
  }
}

TEST(Contact, ReboundReachesRestitutionSquaredOfTheFall) {
  const BounceResult b = droplet_bounce(compute(), default_parameters(), 0.25, 0.5);
  const double fall = b.release_height - b.contact_height;
  EXPECT_NEAR(b.first_rebound - b.contact_height, 0.25 * fall, 0.02 * fall);
}

TEST(Contact, FrictionlessSlideAcceleratesAtGSinAlpha) {
  for (double cfl : {0.1, 0.25, 0.5}) {
    const SlideResult s = droplet_slide(compute(), default_parameters(), cfl, 0.0);
    EXPECT_NEAR(s.acceleration, s.expected_acceleration, 0.02 * s.expected_acceleration)
        << "cfl " << cfl;
    EXPECT_NEAR(s.speed, s.expected_speed, 0.02 * s.expected_speed) << "cfl " << cfl;
  }
}

TEST(Contact, ManningBedFrictionFollowsItsTerminalSpeedLaw) {
  // du/dt = g sin α − g n² u²/D^(4/3), D the lone drop's water depth on the terrain's vertices,
  // against an RK4 integration of the same law. With n = 0.03 s/m^(1/3) the droplet is near its
  // terminal speed after 3 s: friction dominates.
  const SlideResult s = droplet_slide(compute(), default_parameters(), 0.25, 0.03);
  EXPECT_NEAR(s.speed, s.expected_speed, 0.02 * s.expected_speed);
  EXPECT_LT(s.speed, 0.75 * s.expected_acceleration * s.duration) << "friction must slow it";
}

TEST(Contact, RestingClearanceDoesNotDependOnSpawnHeight) {
  Parameters p = default_parameters();
  std::vector<double> clearance;
  for (double spawn_dx : {0.5, 1.0, 2.0, 4.0})
    clearance.push_back(droplet_rest_clearance(compute(), p, spawn_dx * 0.5));  // dx = 0.5 m
  const auto [lo, hi] = std::minmax_element(clearance.begin(), clearance.end());
  EXPECT_LE(*hi - *lo, 0.05 * *lo) << *lo << " to " << *hi << " m";
  // It rests on its lowest point: the centre one contact radius (dx/2) above the ground.
  EXPECT_NEAR(*lo, 0.25, 0.0125);
}

}  // namespace
}  // namespace runnel
