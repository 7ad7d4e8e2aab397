// SPDX-License-Identifier: MIT
#pragma once
#include <epoxy/gl.h>

#include <glm/glm.hpp>
#include <vector>

#include "gl_program.hpp"
#include "runnel/core/heightmap.hpp"

namespace runnel::viewer {

// The water as a surface over the terrain (docs/viewer.md): a mesh on the terrain's grid whose
// height is the ground plus the model's water depth at each vertex, drawn where the depth exceeds
// a threshold, shaded with the surface's smooth vertex normals: Beer–Lambert absorption (thin
// water clear and pale, deep water blue-green and opaque), a Fresnel reflection of the sky, a sun
// highlight, and turbidity from the sediment load that never takes more than a third of the colour;
// the flow is made visible by streaks drifting along the velocity (a flow map: two phases of a
// noise pattern advected and cross-faded, after Vlachos 2010), stronger where the water runs fast.
class WaterRenderer {
 public:
  explicit WaterRenderer(const Heightmap& initial);
  ~WaterRenderer();
  // Per vertex: ground height (m), water depth (m), sediment load (m³/m³) and the velocity (x, z
  // interleaved, m/s; empty: still water).
  void update(const std::vector<float>& ground, const std::vector<float>& depth,
              const std::vector<float>& load, const std::vector<float>& velocity);
  // `seconds`: the model's clock, which moves the flow's streaks.
  void draw(const glm::mat4& view_projection, const glm::vec3& eye, float min_depth,
            float seconds) const;

 private:
  void surface_normals();
  GlProgram program_;
  int nx_, ny_;
  float cell_;
  GLuint vao_ = 0, grid_vbo_ = 0, dynamic_vbo_ = 0, normal_vbo_ = 0, flow_vbo_ = 0, ibo_ = 0;
  GLsizei indices_ = 0;
  std::vector<float> interleaved_, normals_, flow_;
};

}  // namespace runnel::viewer
