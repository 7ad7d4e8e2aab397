// SPDX-License-Identifier: MIT
#include "renderers.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <string>

#include "grid_mesh.hpp"

namespace runnel::viewer {
namespace {

const char* kTerrainVertex = R"(#version 330 core
layout(location = 0) in vec3 grid;     // x, z, initial height
layout(location = 1) in vec4 dynamic;  // height, normal
layout(location = 2) in vec2 water_in;  // water depth (m), mean flow speed (m/s)
uniform mat4 view_projection;
out vec3 world;
out vec3 normal;
out float dh;
out vec2 water;
void main() {
  water = water_in;
  world = vec3(grid.x, dynamic.x, grid.y);
  normal = dynamic.yzw;
  dh = dynamic.x - grid.z;
  gl_Position = view_projection * vec4(world, 1.0);
})";

// The terrain's colour (ground_colour) and lighting (ground_light; ground_light_at from the ground
// texture, for the bed the water refracts); then the water (WaterLayer::kShading) and the brush
// ring.
const char* kTerrainColour = R"(#version 330 core
in vec3 world;
in vec3 normal;
in float dh;
in vec2 water;
uniform float min_height, max_height, overlay_scale, depth_scale;
uniform int overlay;
uniform vec3 brush;  // x, z, radius
uniform int brush_visible;
uniform sampler2D ground;  // the normal's x and z: the bed the water refracts, lit
uniform vec2 ground_texels;
uniform float ground_cell;
out vec4 colour;
vec3 diverging(float t) {  // red (eroded) – white – blue (deposited)
  vec3 red = vec3(0.70, 0.09, 0.17), white = vec3(0.97), blue = vec3(0.13, 0.40, 0.67);
  return t < 0.0 ? mix(white, red, -t) : mix(white, blue, t);
}
vec3 ground_colour(vec3 world, vec3 n, float dh, vec2 water) {
  float h = clamp((world.y - min_height) / max(max_height - min_height, 1e-6), 0.0, 1.0);
  // Texture splatting after Fritz 2016: sand, grass, rock, snow by height; rock on steep slopes.
  // The bands by height follow the terrain's relief in metres: bare rock above the grass only on
  // relief of a few hundred metres, snow on the tops only of mountains (not on a 30-m hill).
  float relief = max_height - min_height;
  vec3 sand = vec3(0.76, 0.70, 0.50), grass = vec3(0.35, 0.55, 0.25), rock = vec3(0.48, 0.45, 0.42),
       snow = vec3(0.95, 0.96, 0.98);
  vec3 base = mix(sand, grass, smoothstep(0.02, 0.15, h));
  base = mix(base, rock, smoothstep(0.55, 0.75, h) * smoothstep(150.0, 400.0, relief));
  base = mix(base, snow, smoothstep(0.82, 0.95, h) * smoothstep(800.0, 1500.0, relief));
  float steep = smoothstep(0.25, 0.45, 1.0 - n.y);
  base = mix(base, rock, steep);
  if (overlay == 1) base = mix(base, diverging(clamp(dh / overlay_scale, -1.0, 1.0)), 0.85);
  if (overlay == 2) base = mix(base, vec3(0.10, 0.35, 0.85), clamp(water.x / depth_scale, 0.0, 0.9));
  if (overlay == 3 && water.x > 0.0) {
    vec3 slow = vec3(0.15, 0.35, 0.85), fast = vec3(0.95, 0.90, 0.20);
    base = mix(base, mix(slow, fast, clamp(water.y / 15.0, 0.0, 1.0)), 0.85);
  }
  return base;
}
float ground_light(vec3 n) {  // Lambert, from a fixed sun, with sky light
  vec3 sun = normalize(vec3(-0.5, 0.8, -0.3));
  return 0.35 + 0.65 * max(dot(n, sun), 0.0);
}
float ground_light_at(vec2 xz) {
  vec2 g = texture(ground, (xz / ground_cell + 0.5) / ground_texels).rg;
  return ground_light(vec3(g.x, sqrt(max(1.0 - dot(g, g), 0.0)), g.y));
}
)";

const char* kTerrainMain = R"(
void main() {
  vec3 n = normalize(normal);
  float light = ground_light(n);
  vec3 lit = with_water(world, ground_colour(world, n, dh, water) * light, light);
  if (brush_visible == 1) {
    float d = length(world.xz - brush.xy);
    float ring = 1.0 - smoothstep(0.0, 0.06 * brush.z, abs(d - brush.z));
    lit = mix(lit, vec3(0.1, 0.5, 1.0), ring);
  }
  colour = vec4(lit, 1.0);
})";

// No water to draw: the ground as it is, without the water's texture reads and shading (on
// llvmpipe every pixel pays for the whole shader, whether a pixel is wet or not).
const char* kNoWater = R"(
vec3 with_water(vec3 world, vec3 ground, float ground_light) { return ground; }
)";

std::string terrain_fragment(bool water) {
  return std::string(kTerrainColour) + (water ? WaterLayer::kShading : kNoWater) + kTerrainMain;
}

const char* kParticleVertex = R"(#version 330 core
layout(location = 0) in vec4 particle;  // x, y, z, value
uniform mat4 view_projection;
uniform float point_size;  // metres · pixels-per-unit-depth
out float value;
void main() {
  value = particle.w;
  gl_Position = view_projection * vec4(particle.xyz, 1.0);
  gl_PointSize = clamp(point_size / gl_Position.w, 1.5, 64.0);
})";

const char* kParticleFragment = R"(#version 330 core
in float value;
uniform int mode;
out vec4 colour;
void main() {
  vec2 p = gl_PointCoord * 2.0 - 1.0;
  float r2 = dot(p, p);
  if (r2 > 1.0) discard;
  vec3 clean = vec3(0.20, 0.50, 0.95), laden = vec3(0.55, 0.36, 0.16);
  vec3 slow = vec3(0.15, 0.35, 0.85), fast = vec3(0.95, 0.95, 0.30);
  vec3 c = mode == 0 ? mix(clean, laden, value) : mix(slow, fast, value);
  colour = vec4(c * (0.75 + 0.25 * sqrt(1.0 - r2)), 0.9);
})";

}  // namespace

TerrainRenderer::TerrainRenderer(const Heightmap& t)
    : program_(kTerrainVertex, terrain_fragment(true).c_str()),
      dry_program_(kTerrainVertex, terrain_fragment(false).c_str()),
      nx_(t.nx),
      ny_(t.ny),
      cell_(t.cell) {
  const std::vector<float> grid = grid_positions(t);
  const std::vector<GLuint> index = grid_triangles(t.nx, t.ny);
  indices_ = static_cast<GLsizei>(index.size());
  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  grid_vbo_ =
      make_buffer(GL_ARRAY_BUFFER, grid.size() * sizeof(float), grid.data(), GL_STATIC_DRAW);
  float_attribute(0, 3);
  dynamic_vbo_ =
      make_buffer(GL_ARRAY_BUFFER, t.size() * 4 * sizeof(float), nullptr, GL_DYNAMIC_DRAW);
  float_attribute(1, 4);
  water_vbo_ = make_buffer(GL_ARRAY_BUFFER, t.size() * 2 * sizeof(float), nullptr, GL_DYNAMIC_DRAW);
  float_attribute(2, 2);
  ibo_ = make_buffer(GL_ELEMENT_ARRAY_BUFFER, index.size() * sizeof(GLuint), index.data(),
                     GL_STATIC_DRAW);
  glBindVertexArray(0);
  ground_ = make_texture();
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RG32F, nx_, ny_, 0, GL_RG, GL_FLOAT, nullptr);
}

TerrainRenderer::~TerrainRenderer() {
  glDeleteTextures(1, &ground_);
  glDeleteBuffers(1, &grid_vbo_);
  glDeleteBuffers(1, &dynamic_vbo_);
  glDeleteBuffers(1, &water_vbo_);
  glDeleteBuffers(1, &ibo_);
  glDeleteVertexArrays(1, &vao_);
}

void TerrainRenderer::update(const std::vector<float>& height, const std::vector<float>& normal) {
  interleaved_.resize(height.size() * 4);
  for (std::size_t k = 0; k < height.size(); ++k) {
    interleaved_[4 * k] = height[k];
    interleaved_[4 * k + 1] = normal[3 * k];
    interleaved_[4 * k + 2] = normal[3 * k + 1];
    interleaved_[4 * k + 3] = normal[3 * k + 2];
  }
  glBindBuffer(GL_ARRAY_BUFFER, dynamic_vbo_);
  glBufferSubData(GL_ARRAY_BUFFER, 0, interleaved_.size() * sizeof(float), interleaved_.data());
  // The normals as a texture too: the bed the water refracts, lit.
  ground_texels_.resize(height.size() * 2);
  for (std::size_t k = 0; k < height.size(); ++k) {
    ground_texels_[2 * k] = normal[3 * k];
    ground_texels_[2 * k + 1] = normal[3 * k + 2];
  }
  glBindTexture(GL_TEXTURE_2D, ground_);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, nx_, ny_, GL_RG, GL_FLOAT, ground_texels_.data());
}

void TerrainRenderer::update_water(const std::vector<float>& depth_and_speed) {
  glBindBuffer(GL_ARRAY_BUFFER, water_vbo_);
  glBufferSubData(GL_ARRAY_BUFFER, 0, depth_and_speed.size() * sizeof(float),
                  depth_and_speed.data());
}

void TerrainRenderer::draw(const glm::mat4& vp, const TerrainLook& look, const WaterLayer& water,
                           const WaterLook& water_look) const {
  const bool wet = !water_look.hidden && water.any();
  const GlProgram& shader = wet ? program_ : dry_program_;
  shader.use();
  if (wet) water.bind(shader, 1, water_look);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, ground_);
  glUniform1i(shader.uniform("ground"), 0);
  glUniform2f(shader.uniform("ground_texels"), static_cast<float>(nx_), static_cast<float>(ny_));
  glUniform1f(shader.uniform("ground_cell"), static_cast<float>(cell_));
  glUniformMatrix4fv(shader.uniform("view_projection"), 1, GL_FALSE, glm::value_ptr(vp));
  glUniform1f(shader.uniform("min_height"), look.min_height);
  glUniform1f(shader.uniform("max_height"), look.max_height);
  glUniform1f(shader.uniform("overlay_scale"), look.overlay_scale);
  glUniform1f(shader.uniform("depth_scale"), depth_scale_);
  glUniform1i(shader.uniform("overlay"), static_cast<int>(look.overlay));
  glUniform3f(shader.uniform("brush"), look.brush.x, look.brush.y, look.brush.z);
  glUniform1i(shader.uniform("brush_visible"), look.brush_visible ? 1 : 0);
  glBindVertexArray(vao_);
  glDrawElements(GL_TRIANGLES, indices_, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
}

ParticleRenderer::ParticleRenderer() : program_(kParticleVertex, kParticleFragment) {
  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  glGenBuffers(1, &vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 0, nullptr);
  glEnableVertexAttribArray(0);
  glBindVertexArray(0);
}

ParticleRenderer::~ParticleRenderer() {
  glDeleteBuffers(1, &vbo_);
  glDeleteVertexArrays(1, &vao_);
}

void ParticleRenderer::update(const std::vector<float>& xyzv) {
  count_ = static_cast<GLsizei>(xyzv.size() / 4);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBufferData(GL_ARRAY_BUFFER, xyzv.size() * sizeof(float), xyzv.data(), GL_STREAM_DRAW);
}

void ParticleRenderer::draw(const glm::mat4& vp, float size_metres, float viewport_height,
                            ParticleColour mode) const {
  if (count_ == 0) return;
  program_.use();
  glUniformMatrix4fv(program_.uniform("view_projection"), 1, GL_FALSE, glm::value_ptr(vp));
  // Projected size: metres × (viewport height / (2 tan(fov/2))) / depth.
  glUniform1f(program_.uniform("point_size"), size_metres * viewport_height / (2.0f * 0.41421f));
  glUniform1i(program_.uniform("mode"), static_cast<int>(mode));
  glEnable(GL_PROGRAM_POINT_SIZE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glBindVertexArray(vao_);
  glDrawArrays(GL_POINTS, 0, count_);
  glBindVertexArray(0);
  glDisable(GL_BLEND);
}

}  // namespace runnel::viewer
