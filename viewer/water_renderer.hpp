// SPDX-License-Identifier: MIT
#pragma once
#include <epoxy/gl.h>

#include <glm/glm.hpp>
#include <vector>

#include "gl_program.hpp"
#include "runnel/models/water_surface.hpp"

namespace runnel::viewer {

// The water as a surface over the terrain (docs/viewer.md): a mesh on the water's own grid (the
// terrain's for the grid models, the particles' spacing for SPH: runnel/models/water_surface.hpp)
// whose height is the ground plus the water depth, drawn where the depth exceeds a threshold,
// shaded with the surface's smooth vertex normals: the bed seen through it refracted and absorbed
// by depth per colour (Beer–Lambert: thin water clear, deep water blue-green), a Fresnel
// reflection of the sky, a sun highlight, and turbidity from the sediment load that never takes
// more than a third of the colour; the flow is made visible by streaks drifting along the velocity
// (a flow map: two phases of a noise pattern advected and cross-faded, after Vlachos 2010),
// stronger where the water runs fast.
class WaterRenderer {
 public:
  // Water thinner than `min_depth` (m) is a wet film, not drawn.
  WaterRenderer(int nx, int ny, double cell, float min_depth);
  ~WaterRenderer();
  // Whether `surface` lies on this renderer's grid.
  bool fits(const WaterSurface& surface) const;
  void update(const WaterSurface& surface);
  // Takes the picture drawn so far (the terrain, width × height) as the bed the water refracts;
  // call it before draw().
  void capture_bed(int width, int height);
  // `seconds`: the model's clock, which moves the flow's streaks; `streak_width` in metres;
  // `normals_only`: the shading normal as colour (x, y, z → red, green, blue), opaque.
  void draw(const glm::mat4& view_projection, const glm::vec3& eye, float seconds,
            float streak_width, bool normals_only = false) const;

 private:
  void surface_normals();
  GlProgram program_;
  int nx_, ny_;
  double cell_;
  float min_depth_;
  GLuint vao_ = 0, grid_vbo_ = 0, dynamic_vbo_ = 0, normal_vbo_ = 0, flow_vbo_ = 0, ibo_ = 0;
  GLuint bed_ = 0;
  int bed_width_ = 0, bed_height_ = 0;
  std::vector<GLuint> all_triangles_, wet_triangles_;
  std::vector<float> interleaved_, normals_, blurred_;
};

}  // namespace runnel::viewer
