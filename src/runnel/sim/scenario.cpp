// SPDX-License-Identifier: MIT
#include "runnel/sim/scenario.hpp"

#include <filesystem>

#include "runnel/core/input_file.hpp"
#include "runnel/core/layers.hpp"

namespace runnel {
namespace {

// A file name relative to the scenario's folder, made absolute-or-normal; "" stays "".
std::string resolved(const std::string& file, const std::string& base_dir) {
  if (file.empty() || base_dir.empty() || !std::filesystem::path(file).is_relative()) return file;
  return (std::filesystem::path(base_dir) / file).lexically_normal().string();
}

}  // namespace

// The parameters that name a file, resolved against the scenario's folder.
constexpr const char* kFileKeys[] = {"terrain.file",         "terrain.graph",
                                     "ground.hardness_mask", "ground.rain_mask",
                                     "ground.frozen_mask",   "stream_power.uplift_file",
                                     "water.depth"};

Parameters parse_scenario(const std::string& text, const std::string& origin,
                          const std::string& base_dir) {
  Parameters params = default_parameters();
  read_parameters_toml(params, text, origin);
  for (const char* key : kFileKeys) {
    if (params.was_set(key)) params.set(key, resolved(params.text(key), base_dir), origin);
  }
  for (std::size_t l = 0; l < params.layers().size(); ++l) {
    const LayerValues& layer = params.layers()[l];
    if (layer.count("thickness_file"))
      params.set_layer_value(l, "thickness_file",
                             resolved(layer_text(layer, "thickness_file"), base_dir));
  }
  return params;
}

std::vector<std::pair<std::string, std::string>> input_files(const Parameters& params) {
  std::vector<std::pair<std::string, std::string>> files;
  for (const char* key : kFileKeys)
    if (params.was_set(key) && !params.text(key).empty()) files.emplace_back(key, params.text(key));
  for (std::size_t l = 0; l < params.layers().size(); ++l) {
    const LayerValues& layer = params.layers()[l];
    if (layer.count("thickness_file"))
      files.emplace_back("layer thickness_file", layer_text(layer, "thickness_file"));
  }
  return files;
}

Parameters load_scenario(const std::string& path) {
  return parse_scenario(read_text_input(path, "scenario file"), path,
                        std::filesystem::path(path).parent_path().string());
}

}  // namespace runnel
