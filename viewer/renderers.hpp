// SPDX-License-Identifier: MIT
#pragma once
#include <epoxy/gl.h>

#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "gl_program.hpp"
#include "runnel/core/heightmap.hpp"
#include "water_layer.hpp"

namespace runnel::viewer {

enum class TerrainOverlay { kNone = 0, kErosion = 1, kWaterDepth = 2, kFlowSpeed = 3 };
enum class ParticleColour { kSediment = 0, kSpeed = 1 };

// How the terrain is coloured this frame.
struct TerrainLook {
  float min_height = 0, max_height = 1;  // the colour bands' range, m
  TerrainOverlay overlay = TerrainOverlay::kNone;
  float overlay_scale = 1;  // the erosion overlay's full colour, m
  glm::vec3 brush{0.0f};    // x, z, radius
  bool brush_visible = false;
};

// The terrain mesh: texture splatting by height and slope (sand, grass, rock, snow; rock on steep
// slopes), Lambert lighting, an erosion/deposition overlay, the water on it (WaterLayer) and the
// rain brush ring.
class TerrainRenderer {
 public:
  explicit TerrainRenderer(const Heightmap& initial);
  ~TerrainRenderer();
  // New heights and vertex normals (3 per vertex) after a simulation step.
  void update(const std::vector<float>& height, const std::vector<float>& normal);
  // Water depth (m) and mean flow speed (m/s) per vertex, from the particles around it.
  void update_water(const std::vector<float>& depth_and_speed);
  void set_depth_scale(float metres) { depth_scale_ = metres; }
  void draw(const glm::mat4& view_projection, const TerrainLook& look, const WaterLayer& water,
            const WaterLook& water_look) const;

 private:
  GlProgram program_, dry_program_;  // with the water's shading, and without (no water)
  GLuint vao_ = 0, grid_vbo_ = 0, dynamic_vbo_ = 0, water_vbo_ = 0, ibo_ = 0;
  float depth_scale_ = 1.0f;
  GLsizei indices_ = 0;
  int nx_, ny_;
  double cell_;
  GLuint ground_ = 0;  // the normals' x and z: the bed the water refracts, lit
  std::vector<float> interleaved_, ground_texels_;
};

// Water particles as round point sprites, coloured by sediment load or by speed.
class ParticleRenderer {
 public:
  ParticleRenderer();
  ~ParticleRenderer();
  // x, y, z, value (in [0, 1]) per particle.
  void update(const std::vector<float>& xyzv);
  void draw(const glm::mat4& view_projection, float point_size_metres, float viewport_height,
            ParticleColour mode) const;

 private:
  GlProgram program_;
  GLuint vao_ = 0, vbo_ = 0;
  GLsizei count_ = 0;
};

}  // namespace runnel::viewer
