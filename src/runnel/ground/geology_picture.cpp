// SPDX-License-Identifier: MIT
#include "runnel/ground/geology_picture.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>

namespace runnel {

void material_colour(const Strata& strata, int m, std::uint8_t rgb[3]) {
  // Colours in the spirit of geological maps, far enough apart to tell neighbours apart.
  static const std::uint8_t kStrata[][3] = {{166, 118, 62},  {236, 196, 92},  {120, 144, 170},
                                            {110, 170, 100}, {200, 150, 200}, {230, 140, 80},
                                            {90, 120, 90},   {180, 180, 120}};
  static const std::uint8_t kBedrock[3] = {196, 96, 110};
  static const std::uint8_t kSediment[3] = {250, 238, 200};
  const std::uint8_t* c = m == strata.bedrock()    ? kBedrock
                          : m == strata.sediment() ? kSediment
                                                   : kStrata[m % 8];
  std::copy(c, c + 3, rgb);
}

RgbImage geology_picture(const Strata& strata, const std::vector<int>& exposed,
                         const Heightmap& terrain) {
  const auto shade = hillshade(terrain);
  const int zoom = picture_zoom(terrain);
  const int map_w = (terrain.nx - 1) * zoom + 1, map_h = (terrain.ny - 1) * zoom + 1;
  const int materials = static_cast<int>(strata.materials.size());
  const int row_h = 20, legend_h = 10 + row_h * materials;
  RgbImage img(std::max(map_w, 300), map_h + legend_h);
  for (int y = 0; y < map_h; ++y) {
    for (int x = 0; x < map_w; ++x) {
      // Nearest vertex: a material is a category, not to be blended.
      const int i = std::min((x + zoom / 2) / zoom, terrain.nx - 1);
      const int j = std::min((y + zoom / 2) / zoom, terrain.ny - 1);
      const std::size_t k = static_cast<std::size_t>(j) * terrain.nx + i;
      std::uint8_t c[3];
      material_colour(strata, exposed[k], c);
      const float s = 0.45f + 0.55f * shade[k];
      img.set(x, y, static_cast<std::uint8_t>(c[0] * s), static_cast<std::uint8_t>(c[1] * s),
              static_cast<std::uint8_t>(c[2] * s));
    }
  }
  std::vector<std::size_t> count(materials, 0);
  for (int m : exposed) ++count[static_cast<std::size_t>(m)];
  for (int m = 0; m < materials; ++m) {
    const int y0 = map_h + 8 + m * row_h;
    std::uint8_t c[3];
    material_colour(strata, m, c);
    for (int y = y0; y < y0 + 14; ++y)
      for (int x = 8; x < 30; ++x) img.set(x, y, c[0], c[1], c[2]);
    std::string name = strata.materials[m].name;
    for (char& ch : name) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    char label[160];
    std::snprintf(label, sizeof label, "%s  %.1f%%", name.c_str(),
                  100.0 * static_cast<double>(count[m]) / static_cast<double>(exposed.size()));
    draw_text(img, 38, y0 + 1, label, 2);
  }
  return img;
}

}  // namespace runnel
