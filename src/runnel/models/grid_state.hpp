// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/core/heightmap.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/terrain/device_terrain.hpp"

namespace runnel {

// The shared state grid models work on (Landlab's grid with its fields): the fixed-point terrain
// (topographic__elevation), its initial state, and named per-vertex device fields from the field
// dictionary. A model asks for its fields once, at construction, and keeps the handles; the
// checkpoint stores every field generically.
// A field of c components lies on the device one plane per component (component c of vertex k at
// c·n + k), so that a kernel reads each component contiguously: interleaved components are what the
// SLP vectoriser packs first, and a work-item loop holding such packs is not vectorised across
// vertices. The host (download, upload, the checkpoint) sees them interleaved, (ny, nx, c).
class GridState {
 public:
  GridState(ComputeContext& compute, const Heightmap& terrain, double height_quantum);

  DeviceTerrain& terrain() { return terrain_; }
  // The initial terrain as the model sees it (rounded to the quantum), and its fixed-point state.
  const Heightmap& initial_terrain() const { return initial_; }
  const std::vector<std::int64_t>& initial_fixed() const { return initial_fixed_; }
  void set_initial_fixed(const std::vector<std::int64_t>& fixed);

  // The handle of a dictionary field; created and zeroed on the first request.
  int field(const std::string& name);
  cl::Buffer& buffer(int handle) { return fields_[static_cast<std::size_t>(handle)].buffer; }
  bool has(const std::string& name) const;
  std::vector<std::string> names() const;

  // Every field's values, and back (same names and sizes).
  std::vector<StoredField> download();
  void upload(const std::vector<StoredField>& fields);
  void upload_field(const StoredField& field);  // one field (same name and size)
  std::vector<float> download_float(const std::string& name);
  std::vector<std::int64_t> download_int64(const std::string& name);
  std::size_t vertices() const { return static_cast<std::size_t>(terrain_.nx()) * terrain_.ny(); }
  // Device memory of the terrain and every field (bytes).
  double device_bytes() const;

 private:
  struct Field {
    std::string name;
    int components;
    bool is_int64;
    cl::Buffer buffer;
    std::size_t bytes() const;
  };
  std::size_t index_of(const std::string& name) const;
  ComputeContext& compute_;
  DeviceTerrain terrain_;
  Heightmap initial_;
  std::vector<std::int64_t> initial_fixed_;
  std::vector<Field> fields_;
  std::size_t vertices_;
};

}  // namespace runnel
