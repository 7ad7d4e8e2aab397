// SPDX-License-Identifier: MIT
#pragma once
#include <epoxy/gl.h>

#include <glm/glm.hpp>
#include <vector>

#include "gl_program.hpp"
#include "runnel/models/water_surface.hpp"

namespace runnel::viewer {

// How the water is drawn this frame.
struct WaterLook {
  glm::vec3 eye{0.0f};
  float seconds = 0;          // the model's clock, which moves the flow's streaks
  float streak_width = 1;     // m
  bool normals_only = false;  // the shading normal as colour, black where dry (--water-normals)
  bool hidden = false;        // no water drawn (--bench measures what it costs)
};

// The water on the terrain (docs/viewer.md, "Water"), shaded per pixel by the terrain's own
// fragment shader, which includes kShading: at each pixel's point on the ground it samples the
// water from textures on the water's own grid (the terrain's for the grid models, the particles'
// spacing for SPH: runnel/models/water_surface.hpp), and where it is deeper than a threshold
// shades it with the surface's smooth normal: the bed seen through it refracted (Snell) and
// absorbed by depth per colour (Beer–Lambert: thin water clear, deep water blue-green), a Fresnel
// reflection of the sky, a sun highlight, and turbidity from the sediment load that never takes
// more than a third of the colour; the flow is made visible by streaks drifting along the
// velocity (a flow map: two phases of a noise pattern advected and cross-faded, after Vlachos
// 2010), stronger where it runs fast. The water is drawn on the ground, not raised by its depth
// (no parallax of its surface): on llvmpipe every pixel drawn costs alike, and a second surface
// over the terrain would double the picture's cost.
class WaterLayer {
 public:
  // The GLSL the terrain's fragment shader includes: with_water(world, ground colour, its
  // Lambert lighting); the terrain's shader provides ground_light_at(xz).
  static const char* const kShading;

  // Water thinner than `min_depth` (m) is a wet film, not drawn.
  explicit WaterLayer(float min_depth);
  ~WaterLayer();
  WaterLayer(const WaterLayer&) = delete;
  WaterLayer& operator=(const WaterLayer&) = delete;
  // The water on its own grid (finer than the terrain's for SPH).
  void update(const WaterSurface& surface);
  // Whether any of it is deep enough to draw.
  bool any() const { return any_; }
  // Its textures on units first_unit … first_unit + 2 and its uniforms in `program` (which
  // includes kShading), drawn as `look` says.
  void bind(const GlProgram& program, int first_unit, const WaterLook& look) const;

 private:
  void surface_slopes(const WaterSurface& surface);
  float min_depth_;
  bool any_ = false;
  static constexpr int kNoiseSize = 64;
  GLuint water_ = 0, slope_ = 0, noise_ = 0;
  int texels_x_ = 0, texels_y_ = 0;
  double cell_ = 1.0;
  std::vector<float> fields_, gradient_, slopes_;
};

}  // namespace runnel::viewer
