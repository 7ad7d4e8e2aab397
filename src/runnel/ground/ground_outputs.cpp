// SPDX-License-Identifier: MIT
#include "runnel/ground/ground_outputs.hpp"

#include "runnel/ground/geology_picture.hpp"
#include "runnel/io/atomic_file.hpp"
#include "runnel/io/hdf5_file.hpp"
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

std::vector<std::string> write_layered_terrain(const std::string& terrain_path,
                                               const Heightmap& terrain, const Strata& strata,
                                               double quantum) {
  const std::size_t n = strata.vertices();
  const auto thickness = [&](int l) {
    std::vector<float> t(n);
    for (std::size_t k = 0; k < n; ++k)
      t[k] = static_cast<float>(
          static_cast<double>(strata.contact(l, k) - strata.contact(l + 1, k)) * quantum);
    return t;
  };
  const std::filesystem::path path(terrain_path);
  if (path.extension() == ".h5") {
    write_path_atomically(terrain_path, [&](const std::string& temporary) {
      H5File f = H5File::create(temporary);
      const std::vector<hsize_t> grid = {static_cast<hsize_t>(terrain.ny),
                                         static_cast<hsize_t>(terrain.nx)};
      f.create_group("/terrain");
      f.write("/terrain/height", terrain.h, grid);
      f.attribute("/terrain", "cell", terrain.cell);
      f.create_group("/layers");
      std::string names;
      for (int l = 0; l < strata.strata; ++l) {
        const Material& m = strata.materials[static_cast<std::size_t>(l)];
        const std::string group = "/layers/" + m.name;
        names += (names.empty() ? "" : ",") + m.name;
        f.create_group(group);
        f.write(group + "/thickness", thickness(l), grid);
        std::vector<float> top(n);
        for (std::size_t k = 0; k < n; ++k)
          top[k] = static_cast<float>(static_cast<double>(strata.contact(l, k)) * quantum);
        f.write(group + "/top", top, grid);
        f.attribute(group, "erodibility", m.erodibility);
        f.attribute(group, "talus_angle_deg", m.talus_angle_deg);
        f.attribute(group, "density", m.density);
      }
      f.attribute("/layers", "names", names);
      f.attribute("/layers", "bedrock", strata.materials[strata.bedrock()].name);
      f.flush();
    });
    return {terrain_path};
  }
  write_terrain(terrain_path, terrain);
  std::vector<std::string> written = {terrain_path};
  for (int l = 0; l < strata.strata; ++l) {
    Heightmap raster = terrain;
    raster.georef.nodata.reset();
    raster.h = thickness(l);
    std::filesystem::path layer = path;
    layer.replace_extension("." + strata.materials[static_cast<std::size_t>(l)].name +
                            path.extension().string());
    write_terrain(layer.string(), raster);
    written.push_back(layer.string());
  }
  return written;
}

}  // namespace runnel
