// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/compute/kernel.hpp"
#include "runnel/core/parameters.hpp"
#include "runnel/ground/strata.hpp"
#include "runnel/io/json.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/terrain/device_terrain.hpp"

namespace runnel {

// The dictionary names of the ground's checkpointed fields.
inline constexpr const char* kGroundSediment = "ground__sediment_thickness";
inline constexpr const char* kGroundContacts = "ground__contact_elevation";
inline constexpr const char* kGroundThickness = "ground__stratum_thickness";

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
  // Per vertex: the active layer's erodibility (float; the particle models read it) and the talus
  // threshold (quanta, int64).
  cl::Buffer& erodibility() { return erodibility_; }
  cl::Buffer& talus_threshold() { return talus_; }
  // The arguments of a grid kernel's bed detachment (BED_DETACHMENT in cl/common.cl):
  // rock_erodibility, sediment_erodibility and ground_sediment.
  void bind_detachment(Kernel& kernel);

  const Strata& strata() const { return strata_; }
  double quantum() const { return terrain_.quantum(); }
  std::vector<std::int64_t> sediment();
  std::vector<int> exposed();

  // The stack for a checkpoint (the sediment and the contacts, and for readers the thickness left
  // of each stratum), and back; restore() then refreshes the factors from the restored heights.
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
  cl::Buffer contacts_, previous_, sediment_, mask_, material_erodibility_, material_talus_;
  cl::Buffer erodibility_, rock_erodibility_, sediment_erodibility_, talus_, exposed_;
  Kernel update_kernel_;
};

// The ground of a run, or nullptr when it has none (has_ground(params) is false).
std::unique_ptr<Ground> make_ground(ComputeContext& compute, const Parameters& params,
                                    DeviceTerrain& terrain, const Heightmap& initial,
                                    const std::vector<std::int64_t>& initial_fixed);

// The per-vertex buffers a model binds for the erodibility and rain-weight arguments of its
// kernels: the ground's and the rain mask's, or one value when there is none (the kernels, compiled
// with GROUND = 0 or RAIN_MASK = 0, never read it).
cl::Buffer placeholder_buffer(ComputeContext& compute);
// BED_DETACHMENT's arguments from `ground`, or placeholders when it is null.
void bind_detachment(Kernel& kernel, Ground* ground, cl::Buffer& placeholder);
// The rain mask (fractions 0 to 1 per vertex) on the device, or a placeholder without one.
cl::Buffer rain_weight_buffer(ComputeContext& compute, const Parameters& params, int nx, int ny);
// The rain mask on the host: the fractions per vertex, checked (finite, in [0, 1]); all 1 without
// one.
std::vector<float> rain_weights(const Parameters& params, int nx, int ny);

// The store's fields, less the ground's (they are restored by the Ground).
std::vector<StoredField> without_ground_fields(const std::vector<StoredField>& fields);

}  // namespace runnel
