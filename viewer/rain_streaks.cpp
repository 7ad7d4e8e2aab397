// SPDX-License-Identifier: MIT
#include "rain_streaks.hpp"

#include <cmath>
#include <cstdint>
#include <glm/gtc/type_ptr.hpp>

namespace runnel::viewer {
namespace {

const char* kStreakVertex = R"(#version 330 core
layout(location = 0) in vec4 point;  // x, y, z, fade (0 at a streak's tail, 1 at its head)
uniform mat4 view_projection;
out float fade;
void main() {
  fade = point.w;
  gl_Position = view_projection * vec4(point.xyz, 1.0);
})";

const char* kStreakFragment = R"(#version 330 core
in float fade;
out vec4 colour;
void main() { colour = vec4(0.86, 0.92, 1.0, 0.75 * fade); })";

// A number in [0, 1) from an index and a stream (a counter-based hash: no state, no order).
float unit_hash(std::uint32_t index, std::uint32_t stream) {
  std::uint32_t h = index * 0x9E3779B9u ^ (stream + 0x7F4A7C15u) * 0x85EBCA6Bu;
  h ^= h >> 16;
  h *= 0x7FEB352Du;
  h ^= h >> 15;
  h *= 0x846CA68Bu;
  h ^= h >> 16;
  return static_cast<float>(h >> 8) * (1.0f / 16777216.0f);
}

}  // namespace

RainStreaks::RainStreaks() : program_(kStreakVertex, kStreakFragment) {
  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  glGenBuffers(1, &vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBufferData(GL_ARRAY_BUFFER, kStreaks * 2 * 4 * sizeof(float), nullptr, GL_STREAM_DRAW);
  glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 4 * sizeof(float), nullptr);
  glEnableVertexAttribArray(0);
  glBindVertexArray(0);
}

RainStreaks::~RainStreaks() {
  glDeleteBuffers(1, &vbo_);
  glDeleteVertexArrays(1, &vao_);
}

void RainStreaks::draw(const glm::mat4& vp, const glm::vec3& centre, float radius,
                       float seconds) const {
  const float fall = 1.5f * radius, length = 0.12f * fall;
  const float speed = 0.8f * fall;  // the whole fall in 1.25 s, whatever the brush's size
  lines_.clear();
  for (int i = 0; i < kStreaks; ++i) {
    const auto k = static_cast<std::uint32_t>(i);
    const float r = radius * std::sqrt(unit_hash(k, 0)), angle = 6.2831853f * unit_hash(k, 1);
    const float x = centre.x + r * std::cos(angle), z = centre.z + r * std::sin(angle);
    const float head =
        centre.y + fall * (1.0f - std::fmod(seconds * speed / fall + unit_hash(k, 2), 1.0f));
    lines_.insert(lines_.end(), {x, head + length, z, 0.0f, x, head, z, 1.0f});
  }
  program_.use();
  glUniformMatrix4fv(program_.uniform("view_projection"), 1, GL_FALSE, glm::value_ptr(vp));
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBufferSubData(GL_ARRAY_BUFFER, 0, lines_.size() * sizeof(float), lines_.data());
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glBindVertexArray(vao_);
  glDrawArrays(GL_LINES, 0, 2 * kStreaks);
  glBindVertexArray(0);
  glDisable(GL_BLEND);
}

}  // namespace runnel::viewer
