// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "runnel/core/heightmap.hpp"
#include "runnel/core/parameters.hpp"
#include "runnel/io/json.hpp"

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
  std::int64_t active_layer = 1;       // quanta (ground.active_layer)
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

// The materials of the scenario's ground, indexed as in Strata.
std::vector<Material> ground_materials(const Parameters& params);
// The strata of a checkpoint: its parameters' materials and its stored contacts (interleaved per
// vertex, `components` = L + 1 of them). Throws an input error when the two disagree.
Strata strata_from_fields(const Parameters& params, int nx, int ny,
                          const std::vector<std::int64_t>& contacts, int components,
                          double quantum);

// Per material the rock eroded (quanta; L + 1 entries) and the vertices where it is exposed (L +
// 2), the loose sediment and the terrain's change (quanta).
struct MaterialTally {
  std::vector<std::int64_t> eroded;
  std::vector<std::size_t> exposed;
  std::int64_t sediment = 0, change = 0;
};
MaterialTally tally_materials(const Strata& strata, const std::vector<std::int64_t>& height_fixed,
                              const std::vector<std::int64_t>& sediment);

// metrics.json's "ground" (and `runnel info --json`'s): per material the rock eroded (m³, kg,
// quanta) and the share of the map where it is exposed; the loose sediment; and the identity Σ(h −
// h0) = Σ sediment − Σ eroded rock, in quanta (layer_balance_quanta, 0 when all is well).
JsonObject ground_summary(const Strata& strata, const std::vector<std::int64_t>& height_fixed,
                          const std::vector<std::int64_t>& sediment, double volume_quantum);

// The material of the rock at a vertex whose rock surface (height less loose sediment) is `rock`:
// the stratum whose band holds it, or the bedrock.
int rock_material(const Strata& strata, std::size_t k, std::int64_t rock);
// The material a map shows at a vertex: the sediment where it fills half the active layer or more,
// else the rock's. The plain C++ oracle of cl/ground.cl, as is:
int exposed_material(const Strata& strata, std::size_t k, std::int64_t rock, std::int64_t sediment);
// The bed's erodibility (before the masks): the active layer's blend of the sediment's and the
// rock's by the share of the active layer the sediment fills.
double bed_erodibility(const Strata& strata, std::size_t k, std::int64_t rock,
                       std::int64_t sediment);

// Rock removed from each material since the start (quanta; L + 1 entries: the strata, then the
// bedrock). The rock surface only falls, so what a vertex lost from stratum l is the length of
// [rock now, initial surface] ∩ the stratum's band: exact, without tracking each event.
std::vector<std::int64_t> eroded_per_material(const Strata& strata,
                                              const std::vector<std::int64_t>& rock);
// Thickness of each stratum left at each vertex (quanta; L planes, stratum l of vertex k at l·n +
// k).
std::vector<std::int64_t> remaining_thickness(const Strata& strata,
                                              const std::vector<std::int64_t>& rock);

}  // namespace runnel
