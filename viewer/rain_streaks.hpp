// SPDX-License-Identifier: MIT
#pragma once
#include <epoxy/gl.h>

#include <glm/glm.hpp>
#include <vector>

#include "gl_program.hpp"

namespace runnel::viewer {

// Rain falling under the brush while it paints: short pale streaks over the brush's disc, falling
// from a height of 1.5 radii to the ground, so the eye sees where the painted water comes from.
// Their positions and phases are a fixed hash of their index: the same disc rains the same way.
class RainStreaks {
 public:
  RainStreaks();
  ~RainStreaks();
  // The disc at `centre` (its ground height in y) of `radius` m; `seconds` moves the streaks.
  void draw(const glm::mat4& view_projection, const glm::vec3& centre, float radius,
            float seconds) const;

 private:
  static constexpr int kStreaks = 400;
  GlProgram program_;
  GLuint vao_ = 0, vbo_ = 0;
  mutable std::vector<float> lines_;
};

}  // namespace runnel::viewer
