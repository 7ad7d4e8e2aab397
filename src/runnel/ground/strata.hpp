// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "runnel/core/heightmap.hpp"
#include "runnel/core/parameters.hpp"

namespace runnel {

// One material of the ground: a stratum, the bedrock or the loose sediment.
struct Material {
  std::string name;
  double erodibility = 1;       // factor on the model's erosion rate
  double talus_angle_deg = 40;  // resolved (never 0)
  double density = 2650;        // kg/m³
};

// The fixed part of the layer stack (docs/layers.md): the strata as bands of the initial ground,
// bounded by contact elevations in counts of the height quantum. Contact 0 is the initial surface;
// stratum l lies in (contact l+1, contact l]; the bedrock lies below contact L. The materials are
// indexed as the kernels index them: 0..L−1 the strata top first, L the bedrock, L+1 the sediment.
struct Strata {
  int nx = 0, ny = 0;
  int strata = 0;                      // L
  std::vector<Material> materials;     // L + 2
  std::vector<std::int64_t> contacts;  // (L + 1) planes of nx·ny: contact l of vertex k at l·n + k
  std::size_t vertices() const { return static_cast<std::size_t>(nx) * ny; }
  std::int64_t contact(int l, std::size_t k) const { return contacts[l * vertices() + k]; }
  int bedrock() const { return strata; }
  int sediment() const { return strata + 1; }
};

// The strata of the scenario's [[layers]] on the run's initial terrain (`initial` in metres for
// the geometry, `initial_fixed` its fixed-point heights). Thickness rasters are read here (input
// errors name the layer and the file).
Strata build_strata(const Parameters& params, const Heightmap& initial,
                    const std::vector<std::int64_t>& initial_fixed, double quantum);

// The material exposed at a vertex whose rock surface (height less loose sediment) is `rock`:
// the sediment when any lies on it, else the stratum whose band holds the rock surface. The plain
// C++ oracle of cl/ground.cl.
int exposed_material(const Strata& strata, std::size_t k, std::int64_t rock, std::int64_t sediment);

// Rock removed from each material since the start (quanta; L + 1 entries: the strata, then the
// bedrock). The rock surface only falls, so what a vertex lost from stratum l is the length of
// [rock now, initial surface] ∩ the stratum's band: exact, without tracking each event.
std::vector<std::int64_t> eroded_per_material(const Strata& strata,
                                              const std::vector<std::int64_t>& rock);
// Thickness of each stratum left at each vertex (quanta; L planes, stratum l of vertex k at l·n +
// k).
std::vector<std::int64_t> remaining_thickness(const Strata& strata,
                                              const std::vector<std::int64_t>& rock);

// A raster on the terrain's vertices, for the masks and thickness files: read in any terrain
// format; one of another size is resampled bilinearly, with a warning on stderr naming `what`.
std::vector<float> read_vertex_raster(const std::string& path, int nx, int ny,
                                      const std::string& what);

}  // namespace runnel
