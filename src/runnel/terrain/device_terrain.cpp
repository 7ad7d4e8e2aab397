// SPDX-License-Identifier: MIT
#include "runnel/terrain/device_terrain.hpp"

#include <cmath>
#include <stdexcept>

#include "runnel/compute/launch.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/text.hpp"

namespace runnel {

DeviceTerrain::DeviceTerrain(ComputeContext& compute, const Heightmap& terrain, double quantum)
    : compute_(compute),
      normals_(compute),
      nx_(terrain.nx),
      ny_(terrain.ny),
      cell_(static_cast<float>(terrain.cell)),
      quantum_(quantum),
      origin_x_(terrain.origin_x),
      origin_z_(terrain.origin_z),
      georef_(terrain.georef),
      tiles_x_(terrain_tiles(terrain.nx)),
      tiles_y_(terrain_tiles(terrain.ny)),
      height_fixed_(compute.context(), CL_MEM_READ_WRITE, terrain.size() * sizeof(cl_long)),
      delta_(compute.context(), CL_MEM_READ_WRITE, terrain.size() * sizeof(cl_long)),
      height_(compute.context(), CL_MEM_READ_WRITE, terrain.size() * sizeof(float)),
      normal_(compute.context(), CL_MEM_READ_WRITE, terrain.size() * 3 * sizeof(float)),
      changed_tiles_(compute.context(), CL_MEM_READ_WRITE,
                     static_cast<std::size_t>(tiles_x_) * tiles_y_ * sizeof(cl_uint)),
      stale_normal_tiles_(compute.context(), CL_MEM_READ_WRITE,
                          static_cast<std::size_t>(tiles_x_) * tiles_y_ * sizeof(cl_uint)),
      apply_(compute, compute.program({"cl/common.cl", "cl/terrain_apply.cl"}), "terrain_apply"),
      view_(compute, compute.program({"cl/common.cl", "cl/terrain_apply.cl"}), "terrain_view"),
      view_changed_(compute, compute.program({"cl/common.cl", "cl/terrain_apply.cl"}),
                    "terrain_view_changed"),
      stale_normals_(compute, compute.program({"cl/common.cl", "cl/terrain_apply.cl"}),
                     "terrain_stale_normals") {
  if (!(quantum > 0)) throw input_error("erosion.height_quantum: must be positive");
  upload(terrain);
}

void DeviceTerrain::upload(const Heightmap& terrain) {
  std::vector<std::int64_t> fixed(terrain.size());
  for (std::size_t k = 0; k < fixed.size(); ++k) {
    const double quanta = terrain.start_height(k) / quantum_;
    if (!(std::fabs(quanta) <= kMaxHeightQuanta)) {
      throw input_error("terrain height " + format_number(terrain.start_height(k)) +
                        " m is not a finite multiple of erosion.height_quantum = " +
                        format_number(quantum_) + " m within 2^53 quanta (the fixed-point " +
                        "heights' range with headroom for the run): raise erosion.height_quantum");
    }
    fixed[k] = std::llround(quanta);
  }
  upload_fixed(fixed);
}

void DeviceTerrain::upload_fixed(const std::vector<std::int64_t>& fixed) {
  for (std::int64_t h : fixed) {
    if (h > kMaxHeightQuanta || h < -kMaxHeightQuanta)
      throw input_error("fixed-point height " + std::to_string(h) +
                        " quanta is beyond 2^53 (no headroom left for the run)");
  }
  auto& q = compute_.queue();
  q.enqueueWriteBuffer(height_fixed_, CL_TRUE, 0, fixed.size() * sizeof(cl_long), fixed.data());
  const cl_long zero = 0;
  q.enqueueFillBuffer(delta_, zero, 0, fixed.size() * sizeof(cl_long));
  refresh_view();
}

void DeviceTerrain::apply() {
  if (deltas_in_use_) {
    refresh_view();
    return;
  }
  const int n = nx_ * ny_;
  view_.set("height_fixed", height_fixed_)
      .set("height", height_)
      .set("n", n)
      .set("quantum", static_cast<float>(quantum_))
      .launch(round_up_work(static_cast<std::size_t>(n)));
  fill_tiles(stale_normal_tiles_, 1);
  normals_stale_ = true;
}

void DeviceTerrain::apply_changed() {
  apply_.set("delta", delta_);
  refresh_changed(apply_);
}

void DeviceTerrain::view_changed() {
  refresh_changed(view_changed_);
}

// terrain_apply or terrain_view_changed over the tiles marked changed, whose normals then turn
// stale.
void DeviceTerrain::refresh_changed(Kernel& pass) {
  pass.set("height_fixed", height_fixed_)
      .set("height", height_)
      .set("nx", nx_)
      .set("ny", ny_)
      .set("quantum", static_cast<float>(quantum_))
      .set("changed", changed_tiles_)
      .set("tiles_x", tiles_x_)
      .launch(round_up_work(static_cast<std::size_t>(nx_) * ny_));
  mark_stale_normals();
}

void DeviceTerrain::mark_stale_normals() {
  stale_normals_.set("changed", changed_tiles_)
      .set("stale", stale_normal_tiles_)
      .set("tiles_x", tiles_x_)
      .set("tiles_y", tiles_y_)
      .launch(round_up_work(static_cast<std::size_t>(tiles_x_) * tiles_y_));
  fill_tiles(changed_tiles_, 0);
  normals_stale_ = true;
}

cl::Buffer& DeviceTerrain::normal() {
  if (normals_stale_) {
    normals_.enqueue(height_, normal_, nx_, ny_, cell_, stale_normal_tiles_, tiles_x_,
                     contact_() ? &contact_ : nullptr, contact_radius_);
    fill_tiles(stale_normal_tiles_, 0);
  }
  normals_stale_ = false;
  return normal_;
}

// Everything may have changed: every tile's heights and normals are refreshed.
void DeviceTerrain::refresh_view() {
  fill_tiles(changed_tiles_, 1);
  fill_tiles(stale_normal_tiles_, 1);
  apply_changed();
}

void DeviceTerrain::fill_tiles(cl::Buffer& tiles, cl_uint value) {
  compute_.queue().enqueueFillBuffer(
      tiles, value, 0, static_cast<std::size_t>(tiles_x_) * tiles_y_ * sizeof(cl_uint));
}

void DeviceTerrain::bind_changes(Kernel& k) {
  deltas_in_use_ = true;
  k.set("delta", delta_).set("changed", changed_tiles_).set("tiles_x", tiles_x_);
}

void DeviceTerrain::bind_fixed_changes(Kernel& k) {
  k.set("height_fixed", height_fixed_).set("changed", changed_tiles_).set("tiles_x", tiles_x_);
}

Heightmap DeviceTerrain::download() {
  Heightmap t(nx_, ny_, cell_);
  t.origin_x = origin_x_;
  t.origin_z = origin_z_;
  t.georef = georef_;
  compute_.queue().enqueueReadBuffer(height_, CL_TRUE, 0, t.size() * sizeof(float), t.h.data());
  return t;
}

std::vector<float> DeviceTerrain::download_normals() {
  std::vector<float> normals(3 * static_cast<std::size_t>(nx_) * ny_);
  compute_.queue().enqueueReadBuffer(normal(), CL_TRUE, 0, normals.size() * sizeof(float),
                                     normals.data());
  return normals;
}

std::vector<std::int64_t> DeviceTerrain::download_fixed() {
  std::vector<std::int64_t> fixed;
  download_fixed(fixed);
  return fixed;
}

void DeviceTerrain::download_fixed(std::vector<std::int64_t>& fixed) {
  fixed.resize(static_cast<std::size_t>(nx_) * ny_);
  compute_.queue().enqueueReadBuffer(height_fixed_, CL_TRUE, 0, fixed.size() * sizeof(cl_long),
                                     fixed.data());
}

void DeviceTerrain::bind(Kernel& k) {
  k.set("terrain_height", height_);
  bind_mesh(k);
}

void DeviceTerrain::bind_extent(Kernel& k) const {
  k.set("domain_x", static_cast<float>(extent_x()));
  k.set("domain_z", static_cast<float>(extent_z()));
}

void DeviceTerrain::bind_mesh(Kernel& k) {
  k.set("terrain_normal", normal()).set("tnx", nx_).set("tny", ny_).set("tcell", cell_);
}

void DeviceTerrain::carry_contact_surface(float radius) {
  contact_ = cl::Buffer(compute_.context(), CL_MEM_READ_WRITE,
                        static_cast<std::size_t>(nx_) * ny_ * sizeof(float));
  contact_radius_ = radius;
  fill_tiles(stale_normal_tiles_, 1);  // every vertex's contact height is still to be computed
  normals_stale_ = true;
}

cl::Buffer& DeviceTerrain::contact() {
  if (!contact_()) throw std::logic_error("DeviceTerrain::contact before carry_contact_surface");
  normal();  // the refresh of stale normals computes their contact heights
  return contact_;
}

void DeviceTerrain::bind_contact(Kernel& k) {
  k.set("terrain_contact", contact());
  bind_mesh(k);
}

}  // namespace runnel
