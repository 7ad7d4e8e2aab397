// SPDX-License-Identifier: MIT
// The [[layers]] keys of a scenario and their validation (docs/layers.md).
#include "runnel/core/layers.hpp"

#include <algorithm>
#include <sstream>

#include "runnel/core/error.hpp"

namespace runnel {

const std::vector<ParamSpec>& layer_table() {
  using T = ParamType;
  static const std::vector<ParamSpec> table = {
      // clang-format off
      {"name", T::kString, "\"\"", "", 0, 0, {}, "the stratum's name (letters, digits, _ and -; unique; not the bedrock's or \"sediment\")"},
      {"thickness", T::kReal, "0", "m", 0, 1e6, {}, "vertical thickness below the stratum above (constant, or the mean with noise_amplitude)"},
      {"noise_amplitude", T::kReal, "0", "m", 0, 1e6, {}, "Münch's multi-layer method: the thickness varies by ± this with the stratum's own fBm noise (clamped at 0)"},
      {"noise_wavelength", T::kReal, "0", "m", 0, 1e9, {}, "the noise's largest feature size; 0: a quarter of the terrain's width"},
      {"noise_octaves", T::kInteger, "4", "1", 1, 16, {}, "octaves of the noise (each half the wavelength and amplitude of the one before)"},
      {"noise_seed", T::kInteger, "1", "1", 0, 9.2e18, {}, "the noise's seed"},
      {"thickness_file", T::kString, "\"\"", "", 0, 0, {}, "the thickness (m) per vertex from a raster (any terrain format; resampled with a warning when its size differs), relative to the scenario"},
      {"depth", T::kReal, "-1", "m", -1, 1e6, {}, "a dipping bed: its lower contact is a plane this deep below the surface at the terrain's centre; -1: not a dipping bed"},
      {"dip", T::kReal, "0", "deg", 0, 89, {}, "a dipping bed: the contact's dip below the horizontal"},
      {"strike", T::kReal, "0", "deg", 0, 360, {}, "a dipping bed: the strike, clockwise from north (the first raster row's side); the contact dips to the right of it"},
      {"erodibility", T::kReal, "1", "1", 0, 1e6, {}, "factor on every model's erosion rate where this stratum is exposed"},
      {"talus_angle", T::kReal, "0", "deg", 0, 89, {}, "talus angle of this stratum (thermal relaxation); 0: thermal.talus_angle"},
      {"density", T::kReal, "2650", "kg/m3", 1, 1e5, {}, "bulk density, for the mass of what is eroded (metrics.json)"},
      // clang-format on
  };
  return table;
}

namespace {

const ParamSpec& layer_spec(const std::string& key) {
  for (const ParamSpec& spec : layer_table())
    if (spec.key == key) return spec;
  throw runtime_error("internal: layer key '" + key + "' is not declared");
}

bool sets(const LayerValues& layer, const std::string& key) {
  return layer.count(key) > 0;
}

}  // namespace

ParamValue layer_value(const LayerValues& layer, const std::string& key) {
  const ParamSpec& spec = layer_spec(key);
  auto it = layer.find(key);
  if (it != layer.end()) return it->second;
  std::string text = spec.default_value;
  if (spec.type == ParamType::kString) return text.substr(1, text.size() - 2);
  if (spec.type == ParamType::kInteger) return static_cast<std::int64_t>(std::stoll(text));
  return std::stod(text);
}

double layer_real(const LayerValues& layer, const std::string& key) {
  return real_value(layer_value(layer, key));
}

std::string layer_text(const LayerValues& layer, const std::string& key) {
  return std::get<std::string>(layer_value(layer, key));
}

LayerShape layer_shape(const LayerValues& layer) {
  if (sets(layer, "thickness_file")) return LayerShape::kRaster;
  if (sets(layer, "depth") && layer_real(layer, "depth") >= 0) return LayerShape::kDipping;
  if (layer_real(layer, "noise_amplitude") > 0) return LayerShape::kNoise;
  return LayerShape::kConstant;
}

void Parameters::add_layer(const LayerValues& given, const std::string& origin) {
  const std::string where = origin + " layers[" + std::to_string(layers_.size() + 1) + "]";
  LayerValues layer;
  for (const auto& entry : given) {
    const std::string& key = entry.first;
    const ParamValue& value = entry.second;
    const auto it = std::find_if(layer_table().begin(), layer_table().end(),
                                 [&key](const ParamSpec& s) { return s.key == key; });
    if (it == layer_table().end())
      throw input_error(where + "." + key + ": unknown layer key (see docs/layers.md)");
    layer[key] = validated_value(*it, value, where + "." + key);
  }
  const std::string name = layer_text(layer, "name");
  if (name.empty()) throw input_error(where + ".name: every layer needs a name");
  if (!std::all_of(name.begin(), name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
      }))
    throw input_error(where + ".name: '" + name + "' may hold only letters, digits, _ and -");
  if (name == "sediment" || name == text("ground.bedrock_name"))
    throw input_error(where + ".name: '" + name + "' is reserved (the loose sediment and " +
                      "the bedrock, ground.bedrock_name)");
  for (const LayerValues& other : layers_)
    if (layer_text(other, "name") == name)
      throw input_error(where + ".name: a layer named '" + name + "' is already defined");
  // One way of giving the lower boundary.
  const bool raster = sets(layer, "thickness_file");
  const bool dipping = sets(layer, "depth") && layer_real(layer, "depth") >= 0;
  const bool noise = layer_real(layer, "noise_amplitude") > 0;
  const int ways = int(raster) + int(dipping) + int(noise || sets(layer, "thickness"));
  if (ways != 1)
    throw input_error(where + ": give exactly one of thickness (with noise_* if it varies), " +
                      "thickness_file or depth (a dipping bed, with dip and strike)");
  if (!dipping && (sets(layer, "dip") || sets(layer, "strike")))
    throw input_error(where + ": dip and strike describe a dipping bed; give its depth too");
  if (raster && layer_text(layer, "thickness_file").empty())
    throw input_error(where + ".thickness_file: empty file name");
  layers_.push_back(std::move(layer));
}

std::string layers_markdown() {
  std::ostringstream out;
  out << "\n## [[layers]]\n\nOne table per stratum, top first (docs/layers.md); give exactly one "
         "of "
         "`thickness`, `thickness_file` or `depth`.\n\n| key | type | default | unit | range | "
         "meaning |\n|---|---|---|---|---|---|\n";
  for (const ParamSpec& p : layer_table()) {
    std::ostringstream range;
    if (p.type == ParamType::kReal || p.type == ParamType::kInteger)
      range << p.min_value << " .. " << p.max_value;
    const char* type = p.type == ParamType::kReal      ? "real"
                       : p.type == ParamType::kInteger ? "integer"
                                                       : "string";
    out << "| `" << p.key << "` | " << type << " | `" << p.default_value << "` | " << p.unit
        << " | " << range.str() << " | " << p.help << " |\n";
  }
  return out.str();
}

}  // namespace runnel
