// SPDX-License-Identifier: MIT
#pragma once
#include <glm/glm.hpp>
#include <vector>

namespace runnel::viewer {

// An orbit camera around a target point: yaw and pitch in radians, distance in metres.
class OrbitCamera {
 public:
  // The reset view: looks at the middle of `points` (a terrain's vertices, or a sample of them)
  // from the default direction, as close as it can with every point inside the picture (of this
  // width / height) and a margin of 4 % of it each side.
  void frame(const std::vector<glm::vec3>& points, float aspect);
  // Whether every point projects inside [-limit, limit] of the picture.
  bool shows(const std::vector<glm::vec3>& points, float aspect, float limit = 1.0f) const;
  void orbit(float dx_pixels, float dy_pixels);
  void pan(float dx_pixels, float dy_pixels, float viewport_height);
  void zoom(float wheel_steps);

  glm::vec3 eye() const;
  glm::mat4 view() const;
  glm::mat4 projection(float aspect) const;
  // The world-space ray through a pixel (origin at the eye, unnormalised direction).
  void ray(double px, double py, int width, int height, glm::dvec3& origin,
           glm::dvec3& direction) const;

 private:
  glm::vec3 target_{0.0f};
  float yaw_ = 0.7f, pitch_ = 0.6f, distance_ = 100.0f, size_ = 100.0f;
};

}  // namespace runnel::viewer
