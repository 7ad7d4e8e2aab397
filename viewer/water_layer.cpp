// SPDX-License-Identifier: MIT
#include "water_layer.hpp"

#include <algorithm>
#include <cstdint>
#include <glm/glm.hpp>

#include "grid_mesh.hpp"

namespace runnel::viewer {

// The water's shading, for the terrain's fragment shader to include: with_water() turns the
// ground's colour at a point into the colour seen there through the water, if any.
const char* const WaterLayer::kShading = R"(
uniform sampler2D water_fields;  // depth (m), load (m³/m³), velocity x and z (m/s)
uniform sampler2D water_slope;  // the water surface normal's x and z
uniform sampler2D water_noise;  // the streaks' noise
uniform vec2 water_texels;  // the water grid's vertices in x and z
uniform float water_cell;   // its spacing, m
uniform vec3 eye;
uniform float min_depth, seconds, streak_scale;
uniform int normals_only;  // --water-normals: the shading normal as colour, black where dry
// The ground's Lambert lighting at a point (the terrain's shader has it): the bed refracted is the
// pixel's own ground colour lit as the ground at the refracted point is.
float ground_light_at(vec2 xz);
float noise(vec2 p) {  // value noise: a tiling 64 × 64 texture of hashed values, bilinear
  return texture(water_noise, p / 64.0).r;
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
vec3 with_water(vec3 world, vec3 ground, float ground_light) {
  vec2 uv = (world.xz / water_cell + 0.5) / water_texels;
  vec4 fields = texture(water_fields, uv);
  float depth = fields.r, load = fields.g;
  vec2 flow = fields.ba;
  if (depth < min_depth) return normals_only == 1 ? vec3(0.0) : ground;
  // The surface's own normal, interpolated between the water grid's vertices: no facets.
  vec2 tilt = texture(water_slope, uv).rg;
  vec3 n = normalize(vec3(tilt.x, sqrt(max(1.0 - dot(tilt, tilt), 0.0)), tilt.y));
  if (normals_only == 1) return 0.5 * n + 0.5;
  vec3 v = normalize(eye - world);
  float cos_view = max(dot(n, v), 0.0);
  float grazing = 1.0 - cos_view, grazing2 = grazing * grazing;
  float fresnel = 0.02 + 0.98 * grazing2 * grazing2 * grazing;  // Schlick, water's F0
  // The bed seen through the water, refracted (Snell, water's index 1.33): the bed point the
  // refracted ray reaches through the depth, against the one the straight ray reaches.
  vec3 t = refract(-v, n, 1.0 / 1.33);
  vec2 shift = depth * (t.xz / max(-t.y, 0.2) + v.xz / max(v.y, 0.2));
  vec3 bed = ground * (ground_light_at(world.xz + shift) / max(ground_light, 0.05));
  // Beer–Lambert per colour over the depth, red absorbed first: thin water clear, the bed tinted
  // blue-green, deep water the colour it scatters. The sediment clouds it, at most by a third. At
  // most 60 % of the bed comes through, so that a film reads as water, not as the ground under it.
  vec3 transmitted = min(exp(-depth * vec3(12.0, 4.0, 2.8)), vec3(0.6));
  vec3 clear = vec3(0.05, 0.34, 0.46), muddy = vec3(0.46, 0.36, 0.22);
  vec3 scattered = mix(clear, muddy, 0.35 * clamp(load * 8.0, 0.0, 1.0));
  vec3 sun = normalize(vec3(-0.5, 0.8, -0.3));
  vec3 under = bed * transmitted + scattered * (0.65 + 0.35 * max(dot(n, sun), 0.0)) *
                                       (1.0 - transmitted);
  vec3 sky = vec3(0.72, 0.82, 0.93);
  float highlight = max(dot(n, normalize(sun + v)), 0.0);  // a Phong lobe of exponent 128
  for (int k = 0; k < 7; ++k) highlight *= highlight;
  vec3 c = mix(under, sky, 0.7 * fresnel) + 0.3 * highlight;
  float speed = length(flow);
  c = mix(c, vec3(0.85, 0.92, 0.95), 0.3 * streaks(world.xz, flow) * smoothstep(0.2, 2.0, speed));
  float shore = smoothstep(min_depth, 3.0 * min_depth, depth);  // thin edges fade in
  return mix(ground, c, shore);
}
)";

namespace {

// Fills `texture` with `data` (channels floats a texel), reallocating when the size changed.
void upload(GLuint texture, int width, int height, bool resized, GLenum format, GLenum internal,
            const std::vector<float>& data) {
  glBindTexture(GL_TEXTURE_2D, texture);
  if (resized)
    glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(internal), width, height, 0, format, GL_FLOAT,
                 data.data());
  else
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, format, GL_FLOAT, data.data());
}

}  // namespace

WaterLayer::WaterLayer(float min_depth) : min_depth_(min_depth) {
  water_ = make_texture();
  slope_ = make_texture();
  noise_ = make_texture();
  std::vector<unsigned char> values(kNoiseSize * kNoiseSize);
  for (std::size_t k = 0; k < values.size(); ++k) {  // a counter-based hash (splitmix64)
    std::uint64_t z = k + 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    values[k] = static_cast<unsigned char>((z ^ (z >> 31)) >> 56);
  }
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, kNoiseSize, kNoiseSize, 0, GL_RED, GL_UNSIGNED_BYTE,
               values.data());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
}

WaterLayer::~WaterLayer() {
  const GLuint textures[] = {water_, slope_, noise_};
  glDeleteTextures(3, textures);
}

void WaterLayer::update(const WaterSurface& s) {
  const std::size_t n = static_cast<std::size_t>(s.nx) * s.ny;
  fields_.resize(4 * n);
  any_ = std::any_of(s.depth.begin(), s.depth.end(), [&](float d) { return d >= min_depth_; });
  for (std::size_t k = 0; k < n; ++k) {
    fields_[4 * k] = s.depth[k];
    fields_[4 * k + 1] = s.load[k];
    fields_[4 * k + 2] = s.velocity[2 * k];
    fields_[4 * k + 3] = s.velocity[2 * k + 1];
  }
  surface_slopes(s);
  const bool resized = s.nx != texels_x_ || s.ny != texels_y_;
  texels_x_ = s.nx;
  texels_y_ = s.ny;
  cell_ = s.cell;
  upload(water_, s.nx, s.ny, resized, GL_RGBA, GL_RGBA32F, fields_);
  upload(slope_, s.nx, s.ny, resized, GL_RG, GL_RG32F, slopes_);
}

// The water surface's normal at each vertex of its grid, from central differences of its height
// (ground + depth) over the wet neighbours (a dry neighbour counts as level with the vertex, so a
// shore does not tilt the water towards the bank), blurred once by 1-2-1 in x and in z over the
// wet vertices, as a narrow-range filter smooths a fluid's depth: the surface's ripples at the
// particles' own scale soften, its shape stays. Kept as the normal's x and z.
void WaterLayer::surface_slopes(const WaterSurface& s) {
  const std::size_t n = static_cast<std::size_t>(s.nx) * s.ny;
  gradient_.assign(2 * n, 0.0f);
  const auto height = [&](int i, int j, float own) {
    if (i < 0 || j < 0 || i >= s.nx || j >= s.ny) return own;
    const std::size_t k = static_cast<std::size_t>(j) * s.nx + i;
    return s.depth[k] > 0.0f ? s.ground[k] + s.depth[k] : own;
  };
  const float cell = static_cast<float>(s.cell);
  for (int j = 0; j < s.ny; ++j)
    for (int i = 0; i < s.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * s.nx + i;
      const float own = s.ground[k] + s.depth[k];
      gradient_[2 * k] = (height(i + 1, j, own) - height(i - 1, j, own)) / (2.0f * cell);
      gradient_[2 * k + 1] = (height(i, j + 1, own) - height(i, j - 1, own)) / (2.0f * cell);
    }
  for (const std::size_t stride : {std::size_t{1}, static_cast<std::size_t>(s.nx)}) {
    slopes_ = gradient_;
    for (int j = 0; j < s.ny; ++j)
      for (int i = 0; i < s.nx; ++i) {
        const std::size_t k = static_cast<std::size_t>(j) * s.nx + i;
        const int pos = stride == 1 ? i : j, end = stride == 1 ? s.nx : s.ny;
        if (pos == 0 || pos + 1 == end || s.depth[k - stride] <= 0.0f ||
            s.depth[k + stride] <= 0.0f)
          continue;
        for (int c = 0; c < 2; ++c)
          slopes_[2 * k + c] =
              0.5f * gradient_[2 * k + c] +
              0.25f * (gradient_[2 * (k - stride) + c] + gradient_[2 * (k + stride) + c]);
      }
    gradient_.swap(slopes_);
  }
  slopes_.resize(2 * n);
  for (std::size_t k = 0; k < n; ++k) {  // the gradient (dh/dx, dh/dz) → the unit normal's x, z
    const glm::vec3 normal =
        glm::normalize(glm::vec3(-gradient_[2 * k], 1.0f, -gradient_[2 * k + 1]));
    slopes_[2 * k] = normal.x;
    slopes_[2 * k + 1] = normal.z;
  }
}

void WaterLayer::bind(const GlProgram& program, int first_unit, const WaterLook& look) const {
  glUniform1f(program.uniform("seconds"), look.seconds);
  glUniform1f(program.uniform("streak_scale"), look.streak_width);
  glUniform3f(program.uniform("eye"), look.eye.x, look.eye.y, look.eye.z);
  glUniform1f(program.uniform("min_depth"), min_depth_);
  glUniform2f(program.uniform("water_texels"), static_cast<float>(texels_x_),
              static_cast<float>(texels_y_));
  glUniform1f(program.uniform("water_cell"), static_cast<float>(cell_));
  glUniform1i(program.uniform("normals_only"), look.normals_only ? 1 : 0);
  glActiveTexture(GL_TEXTURE0 + first_unit);
  glBindTexture(GL_TEXTURE_2D, water_);
  glUniform1i(program.uniform("water_fields"), first_unit);
  glActiveTexture(GL_TEXTURE0 + first_unit + 1);
  glBindTexture(GL_TEXTURE_2D, slope_);
  glUniform1i(program.uniform("water_slope"), first_unit + 1);
  glActiveTexture(GL_TEXTURE0 + first_unit + 2);
  glBindTexture(GL_TEXTURE_2D, noise_);
  glUniform1i(program.uniform("water_noise"), first_unit + 2);
  glActiveTexture(GL_TEXTURE0);
}

}  // namespace runnel::viewer
