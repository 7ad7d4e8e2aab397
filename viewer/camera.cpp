// SPDX-License-Identifier: MIT
#include "camera.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace runnel::viewer {

void OrbitCamera::frame(const glm::vec3& centre, float size) {
  target_ = centre;
  size_ = size;
  distance_ = 1.3f * size;
  yaw_ = 0.7f;
  pitch_ = 0.65f;
}

void OrbitCamera::orbit(float dx, float dy) {
  yaw_ += 0.008f * dx;
  pitch_ = std::clamp(pitch_ + 0.008f * dy, 0.05f, 1.5f);
}

void OrbitCamera::pan(float dx, float dy, float viewport_height) {
  const glm::vec3 forward = glm::normalize(target_ - eye());
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  const glm::vec3 up = glm::cross(right, forward);
  const float metres_per_pixel = 2.0f * distance_ * std::tan(glm::radians(22.5f)) / viewport_height;
  target_ += (-dx * right + dy * up) * metres_per_pixel;
}

void OrbitCamera::zoom(float steps) {
  distance_ = std::clamp(distance_ * std::pow(0.88f, steps), 0.02f * size_, 10.0f * size_);
}

glm::vec3 OrbitCamera::eye() const {
  return target_ + distance_ * glm::vec3(std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_),
                                         std::cos(pitch_) * std::cos(yaw_));
}

glm::mat4 OrbitCamera::view() const {
  return glm::lookAt(eye(), target_, glm::vec3(0, 1, 0));
}

glm::mat4 OrbitCamera::projection(float aspect) const {
  return glm::perspective(glm::radians(45.0f), aspect, 0.005f * size_, 20.0f * size_);
}

void OrbitCamera::ray(double px, double py, int width, int height, glm::dvec3& origin,
                      glm::dvec3& direction) const {
  const glm::dmat4 inverse =
      glm::inverse(glm::dmat4(projection(static_cast<float>(width) / height)) * glm::dmat4(view()));
  const double x = 2.0 * px / width - 1.0, y = 1.0 - 2.0 * py / height;
  glm::dvec4 near = inverse * glm::dvec4(x, y, -1.0, 1.0),
             far = inverse * glm::dvec4(x, y, 1.0, 1.0);
  near /= near.w;
  far /= far.w;
  origin = glm::dvec3(near);
  direction = glm::dvec3(far) - glm::dvec3(near);
}

}  // namespace runnel::viewer
