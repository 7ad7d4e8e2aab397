// SPDX-License-Identifier: MIT
#include "runnel/io/images.hpp"

#include <png.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "runnel/core/error.hpp"
#include "runnel/core/vertex_normals.hpp"
#include "runnel/io/atomic_file.hpp"
#include "runnel/io/font5x7.hpp"

namespace runnel {
namespace {

struct Rgb {
  float r, g, b;
};

Rgb mix(Rgb a, Rgb b, float t) {
  return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t};
}

// Piecewise-linear colour ramp over stops at positions in [0, 1].
Rgb ramp(const std::vector<std::pair<float, Rgb>>& stops, float t) {
  t = std::clamp(t, 0.0f, 1.0f);
  for (std::size_t k = 1; k < stops.size(); ++k) {
    if (t <= stops[k].first) {
      const float span = stops[k].first - stops[k - 1].first;
      return mix(stops[k - 1].second, stops[k].second,
                 span > 0 ? (t - stops[k - 1].first) / span : 0.0f);
    }
  }
  return stops.back().second;
}

// Terrain by height, after the usual hypsometric tints.
const std::vector<std::pair<float, Rgb>> kTerrainRamp = {{0.00f, {0.33f, 0.52f, 0.30f}},
                                                         {0.30f, {0.55f, 0.68f, 0.38f}},
                                                         {0.55f, {0.72f, 0.64f, 0.45f}},
                                                         {0.80f, {0.55f, 0.50f, 0.47f}},
                                                         {1.00f, {0.96f, 0.96f, 0.97f}}};

// Diverging: red (eroded) – white – blue (deposited), after ColorBrewer's RdBu.
const std::vector<std::pair<float, Rgb>> kDivergingRamp = {{0.00f, {0.70f, 0.09f, 0.17f}},
                                                           {0.25f, {0.94f, 0.54f, 0.38f}},
                                                           {0.50f, {0.97f, 0.97f, 0.97f}},
                                                           {0.75f, {0.40f, 0.66f, 0.81f}},
                                                           {1.00f, {0.13f, 0.40f, 0.67f}}};

std::uint8_t to_byte(float v) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

const Glyph* find_glyph(char c) {
  c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const Glyph& g : kFont5x7) {
    if (g.c == c) return &g;
  }
  return nullptr;
}

std::string format_metres(double v) {
  char buf[64];
  const double a = std::fabs(v);
  if (a != 0 && (a < 0.01 || a >= 10000))
    std::snprintf(buf, sizeof buf, "%+.2e m", v);
  else
    std::snprintf(buf, sizeof buf, "%+.3g m", v);
  return buf;
}

}  // namespace

void RgbImage::set(int x, int y, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  if (x < 0 || y < 0 || x >= width || y >= height) return;
  const std::size_t k = 3 * (static_cast<std::size_t>(y) * width + x);
  rgb[k] = r;
  rgb[k + 1] = g;
  rgb[k + 2] = b;
}

void RgbImage::paste(const RgbImage& o, int x0, int y0) {
  for (int y = 0; y < o.height; ++y) {
    for (int x = 0; x < o.width; ++x) {
      const std::size_t k = 3 * (static_cast<std::size_t>(y) * o.width + x);
      set(x0 + x, y0 + y, o.rgb[k], o.rgb[k + 1], o.rgb[k + 2]);
    }
  }
}

std::vector<float> hillshade(const Heightmap& t, double azimuth_deg, double altitude_deg) {
  // Light direction in world axes (x east, y up, z south); azimuth clockwise from north (−z).
  const double az = azimuth_deg * M_PI / 180.0, alt = altitude_deg * M_PI / 180.0;
  const double lx = std::sin(az) * std::cos(alt), lz = -std::cos(az) * std::cos(alt),
               ly = std::sin(alt);
  const std::vector<float> normal = terrain_normals_reference(t);
  std::vector<float> shade(t.size());
  for (std::size_t k = 0; k < shade.size(); ++k) {
    const double lambert = normal[3 * k] * lx + normal[3 * k + 1] * ly + normal[3 * k + 2] * lz;
    shade[k] = static_cast<float>(std::max(0.0, lambert));
  }
  return shade;
}

int picture_zoom(const Heightmap& t) {
  return std::max(1, 512 / std::max(t.nx, t.ny));
}

namespace {
// Bilinear value of a vertex field at pixel (px, py) of a picture `zoom` pixels per cell.
float sample(const std::vector<float>& v, int nx, int ny, int zoom, int px, int py) {
  const float u = std::min(static_cast<float>(px) / zoom, nx - 1.0f);
  const float w = std::min(static_cast<float>(py) / zoom, ny - 1.0f);
  const int i = std::min(static_cast<int>(u), nx - 2 < 0 ? 0 : nx - 2);
  const int j = std::min(static_cast<int>(w), ny - 2 < 0 ? 0 : ny - 2);
  const int i1 = std::min(i + 1, nx - 1), j1 = std::min(j + 1, ny - 1);
  const float fx = u - i, fz = w - j;
  auto at = [&](int a, int b) { return v[static_cast<std::size_t>(b) * nx + a]; };
  return (1 - fx) * (1 - fz) * at(i, j) + fx * (1 - fz) * at(i1, j) + (1 - fx) * fz * at(i, j1) +
         fx * fz * at(i1, j1);
}
// Whether the vertex nearest picture pixel (px, py) is a NODATA hole: holes are drawn in the
// NODATA colour, not as the heights a fill invented.
bool hole_at(const Heightmap& t, int zoom, int px, int py) {
  if (t.georef.holes.empty()) return false;
  const int i = std::min((px + zoom / 2) / zoom, t.nx - 1),
            j = std::min((py + zoom / 2) / zoom, t.ny - 1);
  return t.georef.hole(static_cast<std::size_t>(j) * t.nx + i);
}

}  // namespace

RgbImage terrain_picture(const Heightmap& t, float lo, float hi) {
  const auto shade = hillshade(t);
  const int zoom = picture_zoom(t);
  const int w = (t.nx - 1) * zoom + 1, h = (t.ny - 1) * zoom + 1;
  RgbImage img(w, h);
  const float range = hi > lo ? hi - lo : 1.0f;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (hole_at(t, zoom, x, y)) {
        img.set(x, y, kNodataColour[0], kNodataColour[1], kNodataColour[2]);
        continue;
      }
      const Rgb c = ramp(kTerrainRamp, (sample(t.h, t.nx, t.ny, zoom, x, y) - lo) / range);
      const float s = 0.35f + 0.65f * sample(shade, t.nx, t.ny, zoom, x, y);
      img.set(x, y, to_byte(c.r * s), to_byte(c.g * s), to_byte(c.b * s));
    }
  }
  return img;
}

double erosion_scale(const Heightmap& before, const Heightmap& after) {
  std::vector<float> mags;
  mags.reserve(before.size());
  for (std::size_t k = 0; k < before.size(); ++k) {
    const float d = std::fabs(after.h[k] - before.h[k]);
    if (d > 0) mags.push_back(d);
  }
  if (mags.empty()) return 1e-3;
  const std::size_t at = static_cast<std::size_t>(0.99 * (mags.size() - 1));
  std::nth_element(mags.begin(), mags.begin() + at, mags.end());
  return std::max(1e-9, static_cast<double>(mags[at]));
}

RgbImage erosion_picture(const Heightmap& before, const Heightmap& after, double scale) {
  const auto shade = hillshade(after);
  std::vector<float> change(after.size());
  for (std::size_t k = 0; k < change.size(); ++k) change[k] = after.h[k] - before.h[k];
  const int zoom = picture_zoom(after);
  const int map_w = (after.nx - 1) * zoom + 1, map_h = (after.ny - 1) * zoom + 1;
  const int w = std::max(map_w, 260), bar_h = 54;
  RgbImage img(w, map_h + bar_h);
  for (int y = 0; y < map_h; ++y) {
    for (int x = 0; x < map_w; ++x) {
      if (hole_at(after, zoom, x, y)) {
        img.set(x, y, kNodataColour[0], kNodataColour[1], kNodataColour[2]);
        continue;
      }
      const float t =
          static_cast<float>(0.5 + 0.5 * sample(change, after.nx, after.ny, zoom, x, y) / scale);
      const Rgb c = ramp(kDivergingRamp, t);
      const float s = 0.55f + 0.45f * sample(shade, after.nx, after.ny, zoom, x, y);
      img.set(x, y, to_byte(c.r * s), to_byte(c.g * s), to_byte(c.b * s));
    }
  }
  // Colour bar with its scale: −scale (eroded) … 0 … +scale (deposited).
  const int bar_x = 10, bar_w = w - 20, bar_y = map_h + 6, bar_thick = 12;
  for (int x = 0; x < bar_w; ++x) {
    const Rgb c = ramp(kDivergingRamp, static_cast<float>(x) / (bar_w - 1));
    for (int y = 0; y < bar_thick; ++y)
      img.set(bar_x + x, bar_y + y, to_byte(c.r), to_byte(c.g), to_byte(c.b));
  }
  const int ty = bar_y + bar_thick + 4;
  const std::string left = format_metres(-scale) + " eroded",
                    right = "deposited " + format_metres(scale);
  draw_text(img, bar_x, ty, left, 1);
  draw_text(img, bar_x + bar_w / 2 - text_width("0", 1) / 2, ty, "0", 1);
  draw_text(img, bar_x + bar_w - text_width(right, 1), ty, right, 1);
  draw_text(img, bar_x, ty + 12, "height change dh (m)", 1, 80, 80, 80);
  if (!after.georef.holes.empty()) {
    const std::string nodata = "magenta: no data";
    draw_text(img, bar_x + bar_w - text_width(nodata, 1), ty + 12, nodata, 1, kNodataColour[0],
              kNodataColour[1], kNodataColour[2]);
  }
  return img;
}

RgbImage with_title(const RgbImage& image, const std::string& title) {
  const int bar = 22;
  RgbImage out(std::max(image.width, text_width(title, 2) + 12), image.height + bar);
  draw_text(out, 6, 4, title, 2);
  out.paste(image, 0, bar);
  return out;
}

int text_width(const std::string& text, int scale) {
  return static_cast<int>(text.size()) * 6 * scale;
}

void draw_text(RgbImage& image, int x, int y, const std::string& text, int scale, std::uint8_t r,
               std::uint8_t g, std::uint8_t b) {
  for (std::size_t n = 0; n < text.size(); ++n) {
    const Glyph* glyph = find_glyph(text[n]);
    if (!glyph) continue;
    for (int row = 0; row < 7; ++row) {
      for (int col = 0; col < 5; ++col) {
        if (!(glyph->rows[row] & (0x10 >> col))) continue;
        for (int sy = 0; sy < scale; ++sy) {
          for (int sx = 0; sx < scale; ++sx) {
            image.set(x + static_cast<int>(n) * 6 * scale + col * scale + sx, y + row * scale + sy,
                      r, g, b);
          }
        }
      }
    }
  }
}

void write_png_rgb(const std::string& path, const RgbImage& image) {
  write_file_atomically(path, [&](std::FILE* f) {
    png_image png;
    std::memset(&png, 0, sizeof png);
    png.version = PNG_IMAGE_VERSION;
    png.width = static_cast<png_uint_32>(image.width);
    png.height = static_cast<png_uint_32>(image.height);
    png.format = PNG_FORMAT_RGB;
    if (!png_image_write_to_stdio(&png, f, 0, image.rgb.data(), 0, nullptr)) {
      throw runtime_error(path + ": PNG write failed: " + png.message);
    }
  });
}

}  // namespace runnel
