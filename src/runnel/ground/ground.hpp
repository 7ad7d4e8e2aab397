// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/compute/kernel.hpp"
#include "runnel/core/parameters.hpp"
#include "runnel/core/stored_field.hpp"
#include "runnel/ground/strata.hpp"
#include "runnel/io/json.hpp"
#include "runnel/terrain/bed_fields.hpp"
#include "runnel/terrain/device_terrain.hpp"

namespace runnel {

// The dictionary names of the ground's checkpointed fields.
inline constexpr const char* kGroundSediment = "ground__sediment_thickness";
inline constexpr const char* kGroundContacts = "ground__contact_elevation";
inline constexpr const char* kGroundThickness = "ground__stratum_thickness";
inline constexpr const char* kGroundMask = "ground__erodibility_mask";

// The layer stack of a run on the device (docs/layers.md; host side of cl/ground.cl): the strata's
// contacts, the loose sediment and, derived from them after every step, the exposed material's
// erodibility and talus threshold, which the models' kernels read. Every model calls update() once
// after each step, on the net change of the step, so the bookkeeping is the same for all of them.
class Ground {
 public:
  // `initial` and `initial_fixed`: the run's initial terrain, in metres and in quanta.
  Ground(ComputeContext& compute, const Parameters& params, DeviceTerrain& terrain,
         const Heightmap& initial, const std::vector<std::int64_t>& initial_fixed);

  // Books the step's net height change into the sediment and refreshes the factors.
  void update();
  // Tectonic uplift (stream-power): the whole column rises by `quanta` per vertex, the strata with
  // it, so the uplift is neither loose sediment nor erosion. Call after raising the heights.
  void raise(const std::vector<std::int64_t>& quanta);
  // The rock's erodibility per vertex (× the masks), as the last update() left it.
  std::vector<float> rock_erodibility();
  // The per-vertex fields the models' kernels read, refreshed by update().
  const BedFields& bed() const { return bed_; }
  // What the stack holds on the device (buffer_bytes).
  double device_bytes() const;

  const Strata& strata() const { return strata_; }
  double quantum() const { return terrain_.quantum(); }
  std::vector<std::int64_t> sediment();
  std::vector<int> exposed();

  // Paints the erodibility mask (hardness × frozen: 0 freezes, 1 is the material's own) on these
  // vertices (runnel-viewer). Once painted, the mask is part of the checkpoint.
  void paint_mask(const std::vector<int>& vertices, float value);
  std::vector<float> mask();

  // The stack for a checkpoint (the sediment and the contacts, for readers the thickness left of
  // each stratum, and a painted mask), and back; restore() then refreshes the factors from the
  // restored heights. A checkpoint without a mask restores the mask of the scenario's files.
  std::vector<StoredField> fields();
  void restore(const std::vector<StoredField>& fields);

  // metrics.json's "ground": per material the rock eroded (m³, kg), the exposed share of the map;
  // the sediment lying loose; and the identity Σ(h − h0) = Σ sediment − Σ eroded in quanta.
  JsonObject report();
  // The same per material, as numbers (quanta and vertex counts).
  MaterialTally tally();

 private:
  ComputeContext& compute_;
  DeviceTerrain& terrain_;
  Strata strata_;
  cl::Buffer contacts_, previous_, mask_, material_erodibility_, material_talus_, exposed_;
  BedFields bed_;
  Kernel update_kernel_;
  std::vector<float> scenario_mask_;  // the mask from the scenario's files
  bool mask_painted_ = false;
};

// The ground of a run, or nullptr when it has none (has_ground(params) is false).
std::unique_ptr<Ground> make_ground(ComputeContext& compute, const Parameters& params,
                                    DeviceTerrain& terrain, const Heightmap& initial,
                                    const std::vector<std::int64_t>& initial_fixed);

// The rain mask's `weights` (rain_weights) on the device, or a placeholder without one (the
// kernels, compiled with RAIN_MASK = 0, never read it).
cl::Buffer rain_weight_buffer(ComputeContext& compute, const Parameters& params,
                              const std::vector<float>& weights);
// The rain mask on the host: the fractions per vertex, checked (finite, in [0, 1]); all 1 without
// one.
std::vector<float> rain_weights(const Parameters& params, int nx, int ny);

// The store's fields, less the ground's (they are restored by the Ground).
std::vector<StoredField> without_ground_fields(const std::vector<StoredField>& fields);

}  // namespace runnel
