// SPDX-License-Identifier: MIT
#include "runnel/ground/ground_outputs.hpp"

#include "runnel/ground/geology_picture.hpp"
#include "runnel/io/images.hpp"
#include "runnel/terrain/terrain_io.hpp"

namespace runnel {

JsonObject write_ground_outputs(const std::filesystem::path& out, Ground& ground,
                                const Heightmap& final_terrain) {
  const std::vector<int> exposed = ground.exposed();
  write_png_rgb((out / "geology.png").string(),
                with_title(geology_picture(ground.strata(), exposed, final_terrain),
                           "exposed layer (geological map)"));
  Heightmap map = final_terrain;  // the grid and georeferencing of the terrain
  map.georef.nodata.reset();
  for (std::size_t k = 0; k < map.size(); ++k) map.h[k] = static_cast<float>(exposed[k]);
  write_terrain((out / "exposed_layer.tif").string(), map);
  write_terrain((out / "exposed_layer.npy").string(), map);
  const auto sediment = ground.sediment();
  const double quantum = ground.quantum();
  for (std::size_t k = 0; k < map.size(); ++k)
    map.h[k] = static_cast<float>(static_cast<double>(sediment[k]) * quantum);
  write_terrain((out / "sediment_thickness.tif").string(), map);
  return ground.report()
      .add("exposed_layer_map", "exposed_layer.tif")
      .add("geological_map", "geology.png");
}

}  // namespace runnel
