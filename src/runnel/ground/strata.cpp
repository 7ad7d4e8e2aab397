// SPDX-License-Identifier: MIT
#include "runnel/ground/strata.hpp"
#include "runnel/core/text.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/core/error.hpp"
#include "runnel/core/layers.hpp"
#include "runnel/ground/ground_settings.hpp"
#include "runnel/terrain/noise.hpp"
#include "runnel/terrain/terrain_io.hpp"

namespace runnel {
namespace {

// ground.active_layer in quanta, at least one.
std::int64_t active_layer_quanta(const Parameters& params, double quantum) {
  return std::max<std::int64_t>(1,
                                std::llround(GroundSettings::from(params).active_layer / quantum));
}

double resolved_talus(double angle, const Parameters& params) {
  return angle > 0 ? angle : params.real("thermal.talus_angle");
}

// fBm in about [−1, 1]: octaves of gradient noise, each half the wavelength and amplitude.
double fbm_unit(double x, double z, double wavelength, int octaves, std::uint64_t seed) {
  double sum = 0, norm = 0, amplitude = 1, frequency = 1 / wavelength;
  for (int o = 0; o < octaves; ++o) {
    sum += amplitude * gradient_noise(x * frequency, z * frequency, seed, o);
    norm += amplitude;
    amplitude *= 0.5;
    frequency *= 2;
  }
  return std::clamp(sum / (0.7 * norm), -1.0, 1.0);  // gradient_noise lies in about ±0.7
}

}  // namespace

Strata build_strata(const Parameters& params, const Heightmap& initial,
                    const std::vector<std::int64_t>& initial_fixed, double quantum) {
  Strata s;
  s.nx = initial.nx;
  s.ny = initial.ny;
  s.strata = static_cast<int>(params.layers().size());
  s.active_layer = active_layer_quanta(params, quantum);
  const std::size_t n = s.vertices();
  s.contacts.assign((s.strata + 1) * n, 0);
  std::copy(initial_fixed.begin(), initial_fixed.end(), s.contacts.begin());
  const double width = (initial.nx - 1) * initial.cell, depth_z = (initial.ny - 1) * initial.cell;
  const int ci = initial.nx / 2, cj = initial.ny / 2;
  const double centre_height = initial.at(ci, cj);
  for (int l = 0; l < s.strata; ++l) {
    const LayerValues& layer = params.layers()[l];
    const std::string name = layer_text(layer, "name");
    const LayerShape shape = layer_shape(layer);
    std::vector<float> raster;
    if (shape == LayerShape::kRaster) {
      const std::string file = layer_text(layer, "thickness_file");
      raster =
          read_vertex_raster(file, s.nx, s.ny, "layer " + name + " thickness_file",
                             [](float t) { return t >= 0 ? "" : "a thickness must be ≥ 0 m"; });
    }
    const double thickness = layer_real(layer, "thickness");
    const double amplitude = layer_real(layer, "noise_amplitude");
    const double wavelength = layer_real(layer, "noise_wavelength") > 0
                                  ? layer_real(layer, "noise_wavelength")
                                  : 0.25 * std::max(width, depth_z);
    const int octaves =
        static_cast<int>(std::get<std::int64_t>(layer_value(layer, "noise_octaves")));
    const auto seed =
        static_cast<std::uint64_t>(std::get<std::int64_t>(layer_value(layer, "noise_seed")));
    // A dipping contact: z = z_c − depth − tan(dip) · (distance along the dip direction from the
    // centre). The dip direction is the strike + 90° (right-hand rule), azimuths clockwise from
    // north (−z, the first raster row's side): azimuth θ points along (sin θ, −cos θ) in (x, z).
    const double deg = M_PI / 180.0;
    const double dip_azimuth = (layer_real(layer, "strike") + 90.0) * deg;
    const double dx = std::sin(dip_azimuth), dz = -std::cos(dip_azimuth);
    const double slope = std::tan(layer_real(layer, "dip") * deg);
    const double contact_depth = layer_real(layer, "depth");
    for (int j = 0; j < s.ny; ++j) {
      for (int i = 0; i < s.nx; ++i) {
        const std::size_t k = static_cast<std::size_t>(j) * s.nx + i;
        const double x = i * initial.cell, z = j * initial.cell;
        const std::int64_t top = s.contacts[l * n + k];
        std::int64_t bottom = top;
        switch (shape) {
          case LayerShape::kConstant:
            bottom = top - std::llround(thickness / quantum);
            break;
          case LayerShape::kNoise:
            bottom =
                top - std::llround(std::max(0.0, thickness + amplitude * fbm_unit(x, z, wavelength,
                                                                                  octaves, seed)) /
                                   quantum);
            break;
          case LayerShape::kRaster:
            bottom = top - std::llround(raster[k] / quantum);
            break;
          case LayerShape::kDipping: {
            const double along = (x - ci * initial.cell) * dx + (z - cj * initial.cell) * dz;
            const double plane = centre_height - contact_depth - slope * along;
            bottom = std::min(top, static_cast<std::int64_t>(std::llround(plane / quantum)));
            break;
          }
        }
        s.contacts[(l + 1) * n + k] = std::min(top, bottom);
      }
    }
  }
  s.materials = ground_materials(params);
  return s;
}

std::vector<Material> ground_materials(const Parameters& params) {
  const GroundSettings g = GroundSettings::from(params);
  std::vector<Material> materials;
  for (const LayerValues& layer : params.layers()) {
    materials.push_back({layer_text(layer, "name"), layer_real(layer, "erodibility"),
                         resolved_talus(layer_real(layer, "talus_angle"), params),
                         layer_real(layer, "density")});
  }
  materials.push_back({g.bedrock_name, g.bedrock_erodibility,
                       resolved_talus(g.bedrock_talus_angle, params), g.bedrock_density});
  materials.push_back({"sediment", g.sediment_erodibility,
                       resolved_talus(g.sediment_talus_angle, params), g.sediment_density});
  return materials;
}

MaterialTally tally_materials(const Strata& strata, const std::vector<std::int64_t>& height_fixed,
                              const std::vector<std::int64_t>& sediment) {
  const std::size_t n = strata.vertices();
  MaterialTally t;
  t.exposed.assign(strata.materials.size(), 0);
  std::vector<std::int64_t> rock(n);
  for (std::size_t k = 0; k < n; ++k) {
    rock[k] = height_fixed[k] - sediment[k];
    ++t.exposed[static_cast<std::size_t>(exposed_material(strata, k, rock[k], sediment[k]))];
    t.sediment += sediment[k];
    t.change += height_fixed[k] - strata.contact(0, k);
  }
  t.eroded = eroded_per_material(strata, rock);
  return t;
}

JsonObject ground_summary(const Strata& strata, const std::vector<std::int64_t>& height_fixed,
                          const std::vector<std::int64_t>& sediment, double volume_quantum) {
  const MaterialTally t = tally_materials(strata, height_fixed, sediment);
  const double n = static_cast<double>(strata.vertices());
  std::vector<JsonObject> materials;
  std::int64_t eroded_total = 0;
  for (std::size_t m = 0; m < strata.materials.size(); ++m) {
    const Material& mat = strata.materials[m];
    JsonObject o;
    o.add("name", mat.name)
        .add("erodibility", mat.erodibility)
        .add("talus_angle_deg", mat.talus_angle_deg)
        .add("exposed_fraction", static_cast<double>(t.exposed[m]) / n);
    if (m < t.eroded.size()) {
      eroded_total += t.eroded[m];
      const double volume = static_cast<double>(t.eroded[m]) * volume_quantum;
      o.add("eroded_m3", volume)
          .add("eroded_kg", volume * mat.density)
          .add("eroded_quanta", static_cast<long long>(t.eroded[m]));
    } else {
      o.add("volume_m3", static_cast<double>(t.sediment) * volume_quantum);
    }
    materials.push_back(o);
  }
  return JsonObject()
      .add("materials", materials)
      .add("sediment_m3", static_cast<double>(t.sediment) * volume_quantum)
      .add("rock_eroded_m3", static_cast<double>(eroded_total) * volume_quantum)
      // Σ(h − h0) = Σ sediment − Σ eroded rock, exactly: 0 unless the bookkeeping is broken.
      .add("layer_balance_quanta", static_cast<long long>(t.change - (t.sediment - eroded_total)));
}

Strata strata_from_fields(const Parameters& params, int nx, int ny,
                          const std::vector<std::int64_t>& contacts, int components,
                          double quantum) {
  Strata s;
  s.nx = nx;
  s.ny = ny;
  s.strata = components - 1;
  s.materials = ground_materials(params);
  if (static_cast<int>(s.materials.size()) != s.strata + 2)
    throw input_error("checkpoint: /fields/ground__contact_elevation has " +
                      std::to_string(components) + " contacts, the parameters " +
                      std::to_string(s.materials.size() - 1) + " strata and a bedrock");
  s.active_layer = active_layer_quanta(params, quantum);
  const std::size_t n = s.vertices();
  s.contacts.assign(static_cast<std::size_t>(components) * n, 0);
  for (std::size_t k = 0; k < n; ++k)
    for (int l = 0; l < components; ++l) s.contacts[l * n + k] = contacts[k * components + l];
  return s;
}

int rock_material(const Strata& strata, std::size_t k, std::int64_t rock) {
  int e = 0;
  for (int l = 1; l <= strata.strata; ++l) e += rock <= strata.contact(l, k) ? 1 : 0;
  return e;
}

int exposed_material(const Strata& strata, std::size_t k, std::int64_t rock,
                     std::int64_t sediment) {
  return 2 * sediment >= strata.active_layer ? strata.sediment() : rock_material(strata, k, rock);
}

double bed_erodibility(const Strata& strata, std::size_t k, std::int64_t rock,
                       std::int64_t sediment) {
  const double cover =
      std::min(1.0, static_cast<double>(sediment) / static_cast<double>(strata.active_layer));
  return cover * strata.materials[strata.sediment()].erodibility +
         (1 - cover) * strata.materials[rock_material(strata, k, rock)].erodibility;
}

std::vector<std::int64_t> eroded_per_material(const Strata& strata,
                                              const std::vector<std::int64_t>& rock) {
  std::vector<std::int64_t> eroded(strata.strata + 1, 0);
  for (std::size_t k = 0; k < strata.vertices(); ++k) {
    const std::int64_t surface = strata.contact(0, k);
    for (int l = 0; l <= strata.strata; ++l) {
      const std::int64_t top = std::min(surface, strata.contact(l, k));
      const std::int64_t bottom =
          l < strata.strata ? std::max(rock[k], strata.contact(l + 1, k)) : rock[k];
      eroded[l] += std::max<std::int64_t>(0, top - bottom);
    }
  }
  return eroded;
}

std::vector<std::int64_t> remaining_thickness(const Strata& strata,
                                              const std::vector<std::int64_t>& rock) {
  const std::size_t n = strata.vertices();
  std::vector<std::int64_t> out(strata.strata * n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    for (int l = 0; l < strata.strata; ++l) {
      const std::int64_t top = std::min(rock[k], strata.contact(l, k));
      out[l * n + k] = std::max<std::int64_t>(0, top - strata.contact(l + 1, k));
    }
  }
  return out;
}

}  // namespace runnel
