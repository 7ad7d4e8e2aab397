// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "runnel/core/heightmap.hpp"

namespace runnel {

// An 8-bit RGB picture.
struct RgbImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, 3 bytes per pixel
  RgbImage() = default;
  RgbImage(int w, int h, std::uint8_t fill = 255)
      : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, fill) {}
  void set(int x, int y, std::uint8_t r, std::uint8_t g, std::uint8_t b);
  // Copies `other` with its top-left corner at (x, y).
  void paste(const RgbImage& other, int x, int y);
};

// Shaded relief in [0, 1]: Lambertian light from `azimuth_deg` (clockwise from north) at
// `altitude_deg` above the horizon, with the terrain's true vertical scale.
std::vector<float> hillshade(const Heightmap& terrain, double azimuth_deg = 315.0,
                             double altitude_deg = 45.0);

// Pixels per cell of the pictures of a terrain: small terrains are drawn at least about 512 pixels
// wide (bilinear between the vertices), large ones one pixel per vertex.
int picture_zoom(const Heightmap& terrain);

// NODATA holes in every map picture: a colour no ramp uses, named on the picture.
constexpr std::uint8_t kNodataColour[3] = {255, 0, 255};

// The terrain coloured by height (water-meadow green, grass, earth, rock, snow), shaded by its
// hillshade; its NODATA holes in kNodataColour.
RgbImage terrain_picture(const Heightmap& terrain, float min_height, float max_height);
// Δh = after − before with a diverging colour map (red: eroded, blue: deposited) over the
// hillshade, symmetric around 0 with ± `scale` metres at full colour, and a titled colour bar
// beneath (which names the NODATA colour when the terrain has holes).
RgbImage erosion_picture(const Heightmap& before, const Heightmap& after, double scale);
// A title bar above an image.
RgbImage with_title(const RgbImage& image, const std::string& title);

// Draws text (digits, a–z, . , - + : % ( ) / * & _ =) with a 5×7 pixel font scaled by `scale`.
void draw_text(RgbImage& image, int x, int y, const std::string& text, int scale,
               std::uint8_t r = 0, std::uint8_t g = 0, std::uint8_t b = 0);
int text_width(const std::string& text, int scale);

// Writes an 8-bit RGB PNG atomically.
void write_png_rgb(const std::string& path, const RgbImage& image);

// A robust colour scale for Δh: the 99th percentile of |Δh| (never 0).
double erosion_scale(const Heightmap& before, const Heightmap& after);

}  // namespace runnel
