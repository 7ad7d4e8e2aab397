// SPDX-License-Identifier: MIT
#include "water_renderer.hpp"

#include <algorithm>
#include <glm/gtc/type_ptr.hpp>

#include "grid_mesh.hpp"

namespace runnel::viewer {
namespace {

const char* kWaterVertex = R"(#version 330 core
layout(location = 0) in vec2 grid;     // x, z
layout(location = 1) in vec3 dynamic;  // ground height, water depth, sediment load
layout(location = 2) in vec3 surface_normal;
layout(location = 3) in vec2 velocity;  // m/s, x and z
uniform mat4 view_projection;
out vec3 world;
out vec3 normal;
out vec2 flow;
out float depth;
out float load;
void main() {
  depth = dynamic.y;
  load = dynamic.z;
  normal = surface_normal;
  flow = velocity;
  world = vec3(grid.x, dynamic.x + dynamic.y, grid.y);
  gl_Position = view_projection * vec4(world, 1.0);
})";

const char* kWaterFragment = R"(#version 330 core
in vec3 world;
in vec3 normal;
in vec2 flow;
in float depth;
in float load;
uniform vec3 eye;
uniform float min_depth, seconds, streak_scale;
uniform vec2 viewport;
uniform sampler2D bed_colour;  // the scene drawn so far: the terrain
uniform int normals_only;      // --water-normals: the shading normal as colour
out vec4 colour;
float hash(vec2 p) { return fract(sin(dot(p, vec2(127.1, 311.7))) * 43758.5453); }
float noise(vec2 p) {  // value noise
  vec2 i = floor(p), f = fract(p);
  vec2 u = f * f * (3.0 - 2.0 * f);
  return mix(mix(hash(i), hash(i + vec2(1, 0)), u.x), mix(hash(i + vec2(0, 1)), hash(i + 1.0), u.x),
             u.y);
}
// Streaks drifting with the flow: a noise pattern stretched 4 times along the velocity, advected
// along it for a phase of one second, two phases half a period apart cross-faded so that neither
// drifts for ever.
float streaks(vec2 p, vec2 v) {
  float speed = length(v);
  vec2 along = v / max(speed, 1e-3), across = vec2(-along.y, along.x);
  vec2 q = vec2(dot(p, along) / 4.0, dot(p, across)) / streak_scale;
  float t0 = fract(seconds), t1 = fract(seconds + 0.5);
  float a = noise(q - vec2(speed * t0 / (4.0 * streak_scale), 0.0));
  float b = noise(q - vec2(speed * t1 / (4.0 * streak_scale), 0.0) + 17.0);
  return smoothstep(0.6, 0.9, mix(a, b, abs(2.0 * t0 - 1.0)));
}
void main() {
  if (depth < min_depth) discard;
  // The surface's own normal, smooth across the mesh (WaterRenderer::update): no facets.
  vec3 n = normalize(normal);
  if (normals_only == 1) {
    colour = vec4(0.5 * n + 0.5, 1.0);
    return;
  }
  vec3 v = normalize(eye - world);
  float cos_view = max(dot(n, v), 0.0);
  float fresnel = 0.02 + 0.98 * pow(1.0 - cos_view, 5.0);  // Schlick, water's F0
  // The bed seen through the water, refracted: the picture under the surface, displaced along the
  // surface's slope by more where the water is deeper.
  vec2 uv = gl_FragCoord.xy / viewport + n.xz * 0.03 * clamp(depth, 0.0, 1.0);
  vec3 bed = texture(bed_colour, clamp(uv, vec2(0.0), vec2(1.0))).rgb;
  // Beer–Lambert per colour over the depth, red absorbed first: thin water clear, the bed tinted
  // blue-green, deep water the colour it scatters. The sediment clouds it, at most by a third.
  vec3 transmitted = exp(-depth * vec3(12.0, 4.0, 2.8));
  vec3 clear = vec3(0.05, 0.34, 0.46), muddy = vec3(0.46, 0.36, 0.22);
  vec3 scattered = mix(clear, muddy, 0.35 * clamp(load * 8.0, 0.0, 1.0));
  vec3 sun = normalize(vec3(-0.5, 0.8, -0.3));
  vec3 under = bed * transmitted + scattered * (0.65 + 0.35 * max(dot(n, sun), 0.0)) *
                                       (1.0 - transmitted);
  vec3 sky = vec3(0.72, 0.82, 0.93);
  float highlight = pow(max(dot(n, normalize(sun + v)), 0.0), 120.0);
  vec3 c = mix(under, sky, 0.7 * fresnel) + 0.3 * highlight;
  float speed = length(flow);
  c = mix(c, vec3(0.85, 0.92, 0.95), 0.45 * streaks(world.xz, flow) * smoothstep(0.2, 2.0, speed));
  float shore = smoothstep(min_depth, 3.0 * min_depth, depth);  // thin edges fade out
  colour = vec4(c, shore);
})";

}  // namespace

WaterRenderer::WaterRenderer(int nx, int ny, double cell, float min_depth)
    : program_(kWaterVertex, kWaterFragment), nx_(nx), ny_(ny), cell_(cell), min_depth_(min_depth) {
  const std::size_t n = static_cast<std::size_t>(nx) * ny;
  const std::vector<float> grid = grid_positions(nx, ny, cell);
  all_triangles_ = grid_triangles(nx, ny);  // the terrain's split, so shores match
  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  grid_vbo_ =
      make_buffer(GL_ARRAY_BUFFER, grid.size() * sizeof(float), grid.data(), GL_STATIC_DRAW);
  float_attribute(0, 2);
  dynamic_vbo_ = make_buffer(GL_ARRAY_BUFFER, n * 3 * sizeof(float), nullptr, GL_DYNAMIC_DRAW);
  float_attribute(1, 3);
  normal_vbo_ = make_buffer(GL_ARRAY_BUFFER, n * 3 * sizeof(float), nullptr, GL_DYNAMIC_DRAW);
  float_attribute(2, 3);
  flow_vbo_ = make_buffer(GL_ARRAY_BUFFER, n * 2 * sizeof(float), nullptr, GL_DYNAMIC_DRAW);
  float_attribute(3, 2);
  ibo_ = make_buffer(GL_ELEMENT_ARRAY_BUFFER, all_triangles_.size() * sizeof(GLuint), nullptr,
                     GL_DYNAMIC_DRAW);
  glBindVertexArray(0);
  glGenTextures(1, &bed_);
  glBindTexture(GL_TEXTURE_2D, bed_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

WaterRenderer::~WaterRenderer() {
  glDeleteTextures(1, &bed_);
  glDeleteBuffers(1, &grid_vbo_);
  glDeleteBuffers(1, &dynamic_vbo_);
  glDeleteBuffers(1, &normal_vbo_);
  glDeleteBuffers(1, &flow_vbo_);
  glDeleteBuffers(1, &ibo_);
  glDeleteVertexArrays(1, &vao_);
}

bool WaterRenderer::fits(const WaterSurface& s) const {
  return s.nx == nx_ && s.ny == ny_ && s.cell == cell_;
}

void WaterRenderer::update(const WaterSurface& s) {
  const std::size_t n = static_cast<std::size_t>(nx_) * ny_;
  interleaved_.assign(n * 3, 0.0f);
  for (std::size_t k = 0; k < n; ++k) {
    interleaved_[3 * k] = s.ground[k];
    interleaved_[3 * k + 1] = s.depth[k];
    interleaved_[3 * k + 2] = s.load[k];
  }
  glBindBuffer(GL_ARRAY_BUFFER, dynamic_vbo_);
  glBufferSubData(GL_ARRAY_BUFFER, 0, interleaved_.size() * sizeof(float), interleaved_.data());
  surface_normals();
  glBindBuffer(GL_ARRAY_BUFFER, normal_vbo_);
  glBufferSubData(GL_ARRAY_BUFFER, 0, normals_.size() * sizeof(float), normals_.data());
  glBindBuffer(GL_ARRAY_BUFFER, flow_vbo_);
  glBufferSubData(GL_ARRAY_BUFFER, 0, 2 * n * sizeof(float), s.velocity.data());
  // Only the triangles with water deep enough to draw at a corner: the dry rest of the grid would
  // cost the rasteriser a fragment for every pixel of terrain, each discarded.
  wet_triangles_.clear();
  for (std::size_t t = 0; t < all_triangles_.size(); t += 3) {
    const GLuint* v = &all_triangles_[t];
    if (s.depth[v[0]] >= min_depth_ || s.depth[v[1]] >= min_depth_ || s.depth[v[2]] >= min_depth_)
      wet_triangles_.insert(wet_triangles_.end(), v, v + 3);
  }
  glBindVertexArray(vao_);
  glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, 0, wet_triangles_.size() * sizeof(GLuint),
                  wet_triangles_.data());
  glBindVertexArray(0);
}

// The water surface's normal at each vertex, from central differences of its height (ground +
// depth) over the wet neighbours (a dry neighbour counts as level with the vertex, so a shore does
// not tilt the water towards the bank).
void WaterRenderer::surface_normals() {
  normals_.assign(interleaved_.size(), 0.0f);
  const auto surface = [&](int i, int j, float own) {
    if (i < 0 || j < 0 || i >= nx_ || j >= ny_) return own;
    const std::size_t k = static_cast<std::size_t>(j) * nx_ + i;
    return interleaved_[3 * k + 1] > 0.0f ? interleaved_[3 * k] + interleaved_[3 * k + 1] : own;
  };
  const float cell = static_cast<float>(cell_);
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * nx_ + i;
      const float own = interleaved_[3 * k] + interleaved_[3 * k + 1];
      const float dx = (surface(i + 1, j, own) - surface(i - 1, j, own)) / (2.0f * cell);
      const float dz = (surface(i, j + 1, own) - surface(i, j - 1, own)) / (2.0f * cell);
      normals_[3 * k] = -dx;
      normals_[3 * k + 1] = 1.0f;
      normals_[3 * k + 2] = -dz;
    }
  // The slopes blurred once by 1-2-1 in x and in z over the wet vertices, as a narrow-range filter
  // smooths a fluid's depth: the surface's ripples at the particles' own scale soften, its shape
  // stays.
  for (const std::size_t stride : {std::size_t{1}, static_cast<std::size_t>(nx_)}) {
    blurred_ = normals_;
    for (int j = 0; j < ny_; ++j)
      for (int i = 0; i < nx_; ++i) {
        const std::size_t k = static_cast<std::size_t>(j) * nx_ + i;
        const int pos = stride == 1 ? i : j, end = stride == 1 ? nx_ : ny_;
        if (pos == 0 || pos + 1 == end || interleaved_[3 * (k - stride) + 1] <= 0.0f ||
            interleaved_[3 * (k + stride) + 1] <= 0.0f)
          continue;
        for (int c = 0; c < 3; c += 2)
          blurred_[3 * k + c] =
              0.5f * normals_[3 * k + c] +
              0.25f * (normals_[3 * (k - stride) + c] + normals_[3 * (k + stride) + c]);
      }
    normals_.swap(blurred_);
  }
  for (std::size_t k = 0; k < normals_.size(); k += 3) {
    const glm::vec3 n = glm::normalize(glm::vec3(normals_[k], normals_[k + 1], normals_[k + 2]));
    normals_[k] = n.x;
    normals_[k + 1] = n.y;
    normals_[k + 2] = n.z;
  }
}

// The picture drawn so far (the terrain) into the bed texture the water refracts.
void WaterRenderer::capture_bed(int width, int height) {
  glBindTexture(GL_TEXTURE_2D, bed_);
  if (width != bed_width_ || height != bed_height_) {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, width, height, 0, GL_RGB, GL_UNSIGNED_BYTE, nullptr);
    bed_width_ = width;
    bed_height_ = height;
  }
  glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, width, height);
}

void WaterRenderer::draw(const glm::mat4& vp, const glm::vec3& eye, float seconds,
                         float streak_width, bool normals_only) const {
  if (wet_triangles_.empty()) return;
  program_.use();
  glUniform1f(program_.uniform("seconds"), seconds);
  glUniform1f(program_.uniform("streak_scale"), streak_width);
  glUniformMatrix4fv(program_.uniform("view_projection"), 1, GL_FALSE, glm::value_ptr(vp));
  glUniform3f(program_.uniform("eye"), eye.x, eye.y, eye.z);
  glUniform1f(program_.uniform("min_depth"), min_depth_);
  glUniform2f(program_.uniform("viewport"), static_cast<float>(bed_width_),
              static_cast<float>(bed_height_));
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, bed_);
  glUniform1i(program_.uniform("bed_colour"), 0);
  glUniform1i(program_.uniform("normals_only"), normals_only ? 1 : 0);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDepthMask(GL_FALSE);  // the terrain under the water stays in the depth buffer
  glBindVertexArray(vao_);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(wet_triangles_.size()), GL_UNSIGNED_INT,
                 nullptr);
  glBindVertexArray(0);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
}

}  // namespace runnel::viewer
