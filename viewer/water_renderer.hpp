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
// a threshold, with Beer–Lambert absorption (deeper is less transparent), a Fresnel reflection of
// the sky, a sun highlight and a tint from clear blue to muddy brown by the sediment load.
class WaterRenderer {
 public:
  explicit WaterRenderer(const Heightmap& initial);
  ~WaterRenderer();
  // Per vertex: ground height (m), water depth (m), sediment load (m³/m³).
  void update(const std::vector<float>& ground, const std::vector<float>& depth,
              const std::vector<float>& load);
  void draw(const glm::mat4& view_projection, const glm::vec3& eye, float min_depth) const;

 private:
  GlProgram program_;
  GLuint vao_ = 0, grid_vbo_ = 0, dynamic_vbo_ = 0, ibo_ = 0;
  GLsizei indices_ = 0;
  std::vector<float> interleaved_;
};

}  // namespace runnel::viewer
