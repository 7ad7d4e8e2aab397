// SPDX-License-Identifier: MIT
#include "camera.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace runnel::viewer {

void OrbitCamera::frame(const std::vector<glm::vec3>& points, float aspect) {
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& p : points) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  target_ = 0.5f * (lo + hi);
  size_ = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-3f});
  yaw_ = 0.7f;
  pitch_ = 0.65f;
  // The projected points draw together as the camera backs away: bisect on the distance for the
  // closest one that keeps every point within 92 % of the picture, then centre the picture on the
  // points' projection (the box's centre is not the silhouette's) and fit again.
  const float tan_half = std::tan(glm::radians(22.5f));
  for (int round = 0; round < 3; ++round) {
    float near = 0.05f * size_, far = 20.0f * size_;
    for (int k = 0; k < 40; ++k) {
      distance_ = 0.5f * (near + far);
      (shows(points, aspect, 0.92f) ? far : near) = distance_;
    }
    distance_ = far;
    const glm::mat4 vp = projection(aspect) * view();
    glm::vec2 ndc_lo(1e30f), ndc_hi(-1e30f);
    for (const glm::vec3& point : points) {
      const glm::vec4 q = vp * glm::vec4(point, 1.0f);
      ndc_lo = glm::min(ndc_lo, glm::vec2(q) / q.w);
      ndc_hi = glm::max(ndc_hi, glm::vec2(q) / q.w);
    }
    const glm::vec2 off = 0.5f * (ndc_lo + ndc_hi);  // where the silhouette's middle is
    const glm::vec3 forward = glm::normalize(target_ - eye());
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    const glm::vec3 up = glm::cross(right, forward);
    target_ += distance_ * tan_half * (off.x * aspect * right + off.y * up);
  }
}

bool OrbitCamera::shows(const std::vector<glm::vec3>& points, float aspect, float limit) const {
  const glm::mat4 vp = projection(aspect) * view();
  for (const glm::vec3& point : points) {
    const glm::vec4 p = vp * glm::vec4(point, 1.0f);
    if (p.w <= 0 || std::fabs(p.x / p.w) > limit || std::fabs(p.y / p.w) > limit) return false;
  }
  return true;
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
