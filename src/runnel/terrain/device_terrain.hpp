// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/compute/kernel.hpp"
#include "runnel/core/heightmap.hpp"
#include "runnel/terrain/terrain_normals.hpp"

namespace runnel {

// The terrain on the device. The state is fixed point: 64-bit integer counts of a height quantum
// q (m), so every erosion, deposition and talus exchange moves an exact integer amount and the
// terrain volume is an exact integer sum. Kernels read a float view (height) and vertex normals,
// refreshed after each application of the per-step changes (`apply`), and add their changes to
// `delta` with 64-bit integer atomics. Host side of cl/terrain_apply.cl.
// Heights are at most 2^53 quanta from zero: exact in a double, and 1000 times below the 64-bit
// limit, so no run's erosion and deposition can wrap them.
inline constexpr std::int64_t kMaxHeightQuanta = std::int64_t{1} << 53;

class DeviceTerrain {
 public:
  DeviceTerrain(ComputeContext& compute, const Heightmap& terrain, double quantum = 1e-6);
  // Replaces the heights (same size): rounds them to the quantum, refreshes the view and normals.
  void upload(const Heightmap& terrain);
  void upload_fixed(const std::vector<std::int64_t>& fixed);
  // Adds the accumulated deltas to the fixed-point heights, clears them and refreshes the view,
  // after a change anywhere (a kernel that wrote height_fixed). Where no kernel was ever given the
  // deltas (bind_changes, delta()), only the view is refreshed: the grid models write the heights
  // directly, and reading and clearing deltas that are all 0 was two thirds of the pass. The
  // normals are refreshed when next asked for (normal(), bind()): the grid models never read them,
  // and recomputing them every step cost the pipe model a sixth of its time.
  void apply();
  // The same for the tiles marked changed by the kernels that added deltas (bind_changes), and
  // only their normals turn stale: a step's cost follows the water, not the terrain's size.
  void apply_changed();
  // The same for a step whose kernels added straight to the fixed heights (bind_fixed_changes):
  // only the marked tiles' view is refreshed.
  void view_changed();
  // The float view as a heightmap, and the exact fixed-point state.
  Heightmap download();
  std::vector<std::int64_t> download_fixed();
  // The same into `fixed` (resized), whose memory a caller stepping every frame keeps.
  void download_fixed(std::vector<std::int64_t>& fixed);
  std::vector<float> download_normals();  // 3 floats a vertex, refreshed first if stale

  // The arguments every terrain-aware kernel takes: terrain_height, terrain_normal, tnx, tny,
  // tcell.
  void bind(Kernel& kernel);
  // From now on the normals' refresh also keeps the vertex heights of the contact surface `radius`
  // above the terrain (raised_height in cl/common.cl), bit for bit what offset_surface computes at
  // that radius: the SPH drift samples that surface several times a particle and step, and a kept
  // height is one load instead of two and a division. 4 bytes a vertex.
  void carry_contact_surface(float radius);
  // Those heights, refreshed first if stale (carry_contact_surface first).
  cl::Buffer& contact();
  // terrain_contact (contact()), terrain_normal, tnx, tny, tcell.
  void bind_contact(Kernel& kernel);
  // terrain_normal, tnx, tny, tcell: what every sampler of the mesh takes beside its heights.
  void bind_mesh(Kernel& kernel);
  // Sets `domain_x`, `domain_z`: the extent the outflow and the tank walls are at (m).
  void bind_extent(Kernel& kernel) const;
  cl::Buffer& height() { return height_; }
  cl::Buffer& normal();
  cl::Buffer& delta() {
    deltas_in_use_ = true;
    return delta_;
  }
  // The arguments of a kernel that adds to the deltas: delta, changed (the tiles it marks; see
  // mark_changed_tiles in cl/common.cl) and tiles_x.
  void bind_changes(Kernel& kernel);
  // The arguments height_fixed, changed and tiles_x, for a kernel that adds straight to the fixed
  // heights because it reads only the float view while it adds (the droplets): a step needs no
  // deltas to clear. Finish the step with view_changed().
  void bind_fixed_changes(Kernel& kernel);
  cl::Buffer& changed_tiles() { return changed_tiles_; }
  int tiles_x() const { return tiles_x_; }
  int tiles_y() const { return tiles_y_; }
  cl::Buffer& height_fixed() { return height_fixed_; }
  int nx() const { return nx_; }
  int ny() const { return ny_; }
  float cell() const { return cell_; }
  double quantum() const { return quantum_; }
  // m³ per quantum count at one vertex: the volume quantum of sediment.
  double volume_quantum() const { return quantum_ * static_cast<double>(cell_) * cell_; }
  double extent_x() const { return (nx_ - 1) * static_cast<double>(cell_); }
  double extent_z() const { return (ny_ - 1) * static_cast<double>(cell_); }

 private:
  void refresh_view();
  // terrain_apply or terrain_view_changed over the changed tiles, then mark_stale_normals().
  void refresh_changed(Kernel& pass);
  // Marks the changed tiles' normals, and their neighbours', stale, then clears the changed tiles.
  void mark_stale_normals();
  void fill_tiles(cl::Buffer& tiles, cl_uint value);
  ComputeContext& compute_;
  TerrainNormals normals_;
  int nx_, ny_;
  float cell_;
  double quantum_;
  double origin_x_, origin_z_;
  Georeference georef_;
  int tiles_x_, tiles_y_;
  cl::Buffer height_fixed_, delta_, height_, normal_;
  cl::Buffer contact_;  // the contact surface's vertex heights, once carried
  float contact_radius_ = 0;
  cl::Buffer changed_tiles_, stale_normal_tiles_;  // one cl_uint per tile, 1: marked
  bool normals_stale_ = true;                      // some tile of stale_normal_tiles_ may be marked
  Kernel apply_, view_, view_changed_, stale_normals_;
  bool deltas_in_use_ = false;  // some kernel may add to delta_ (apply() must read it)
};

}  // namespace runnel
