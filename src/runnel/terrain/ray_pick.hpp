// SPDX-License-Identifier: MIT
#pragma once
#include <optional>

#include "runnel/core/heightmap.hpp"

namespace runnel {

struct RayHit {
  double t;        // ray parameter: hit = origin + t · direction
  double x, y, z;  // m
};

// The first point where the ray origin + t·direction (t ≥ 0) meets the terrain's triangles from
// above: the tiles under the ray are walked in order (2-D DDA) and each tile's two triangles tested
// with Möller–Trumbore, as the particles' collision does (cl/collide.cl), in double precision.
// Used to put the viewer's rain brush where the cursor points.
std::optional<RayHit> pick_terrain(const Heightmap& terrain, const double origin[3],
                                   const double direction[3]);

}  // namespace runnel
