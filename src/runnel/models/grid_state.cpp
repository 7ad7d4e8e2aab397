// SPDX-License-Identifier: MIT
#include "runnel/models/grid_state.hpp"

#include "runnel/core/error.hpp"
#include "runnel/models/fields.hpp"

namespace runnel {

namespace {

// A rows × cols matrix, row-major, transposed. Device (one plane per component: components ×
// vertices) to host (components of a vertex together, the checkpoint's (ny, nx, c)): rows =
// components; back: rows = vertices.
template <typename T>
std::vector<T> transposed(const std::vector<T>& values, std::size_t rows, std::size_t cols) {
  if (rows == 1 || cols == 1) return values;
  std::vector<T> out(values.size());
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t c = 0; c < cols; ++c) out[c * rows + r] = values[r * cols + c];
  return out;
}

}  // namespace

GridState::GridState(ComputeContext& compute, const Heightmap& terrain, double height_quantum)
    : compute_(compute),
      terrain_(compute, terrain, height_quantum),
      initial_(terrain),
      vertices_(terrain.size()) {
  set_initial_fixed(terrain_.download_fixed());
}

void GridState::set_initial_fixed(const std::vector<std::int64_t>& fixed) {
  initial_fixed_ = fixed;
  for (std::size_t k = 0; k < initial_.size(); ++k)
    initial_.h[k] = static_cast<float>(static_cast<double>(fixed[k]) * terrain_.quantum());
}

double GridState::device_bytes() const {
  double bytes = 32.0 * static_cast<double>(vertices_);  // fixed point, deltas, float view, normals
  for (const Field& f : fields_) bytes += static_cast<double>(vertices_ * f.bytes());
  return bytes;
}

std::size_t GridState::Field::bytes() const {
  return static_cast<std::size_t>(components) * (is_int64 ? 8 : 4);
}

std::size_t GridState::index_of(const std::string& name) const {
  for (std::size_t k = 0; k < fields_.size(); ++k)
    if (fields_[k].name == name) return k;
  return fields_.size();
}

int GridState::field(const std::string& name) {
  const std::size_t found = index_of(name);
  if (found < fields_.size()) return static_cast<int>(found);
  const FieldDescription& d = field_description(name);
  if (d.location != FieldLocation::kVertex || name == kTopographicElevation ||
      (d.type != FieldType::kFloat32 && d.type != FieldType::kInt64)) {
    throw std::logic_error(name + " is not a vertex field a grid model can own");
  }
  Field f{name, d.components, d.type == FieldType::kInt64, {}};
  f.buffer = cl::Buffer(compute_.context(), CL_MEM_READ_WRITE, vertices_ * f.bytes());
  if (f.is_int64)
    compute_.queue().enqueueFillBuffer(f.buffer, cl_long{0}, 0, vertices_ * f.bytes());
  else
    compute_.queue().enqueueFillBuffer(f.buffer, 0.0f, 0, vertices_ * f.bytes());
  fields_.push_back(std::move(f));
  return static_cast<int>(fields_.size() - 1);
}

bool GridState::has(const std::string& name) const {
  return index_of(name) < fields_.size();
}

std::vector<std::string> GridState::names() const {
  std::vector<std::string> out;
  for (const Field& f : fields_) out.push_back(f.name);
  return out;
}

std::vector<StoredField> GridState::download() {
  std::vector<StoredField> out;
  for (const Field& f : fields_) {
    StoredField s;
    s.name = f.name;
    s.components = f.components;
    if (f.is_int64)
      s.i64 = download_int64(f.name);
    else
      s.f32 = download_float(f.name);
    out.push_back(std::move(s));
  }
  return out;
}

void GridState::upload(const std::vector<StoredField>& stored) {
  if (stored.size() != fields_.size())
    throw input_error("checkpoint: it holds " + std::to_string(stored.size()) +
                      " grid fields, the model has " + std::to_string(fields_.size()));
  for (const StoredField& s : stored) upload_field(s);
}

void GridState::upload_field(const StoredField& s) {
  const std::size_t k = index_of(s.name);
  if (k == fields_.size())
    throw input_error("checkpoint: field " + s.name + " does not belong to this model");
  Field& f = fields_[k];
  const std::size_t count = vertices_ * static_cast<std::size_t>(f.components);
  const bool ok =
      s.components == f.components && (f.is_int64 ? s.i64.size() == count : s.f32.size() == count);
  if (!ok) throw input_error("checkpoint: field " + s.name + " has the wrong size or type");
  if (f.is_int64) {
    const auto device = transposed(s.i64, vertices_, static_cast<std::size_t>(f.components));
    compute_.queue().enqueueWriteBuffer(f.buffer, CL_TRUE, 0, vertices_ * f.bytes(), device.data());
  } else {
    const auto device = transposed(s.f32, vertices_, static_cast<std::size_t>(f.components));
    compute_.queue().enqueueWriteBuffer(f.buffer, CL_TRUE, 0, vertices_ * f.bytes(), device.data());
  }
}

std::vector<float> GridState::download_float(const std::string& name) {
  Field& f = fields_.at(index_of(name));
  std::vector<float> out(vertices_ * static_cast<std::size_t>(f.components));
  compute_.queue().enqueueReadBuffer(f.buffer, CL_TRUE, 0, out.size() * 4, out.data());
  return transposed(out, static_cast<std::size_t>(f.components), vertices_);
}

std::vector<std::int64_t> GridState::download_int64(const std::string& name) {
  Field& f = fields_.at(index_of(name));
  std::vector<std::int64_t> out(vertices_ * static_cast<std::size_t>(f.components));
  compute_.queue().enqueueReadBuffer(f.buffer, CL_TRUE, 0, out.size() * 8, out.data());
  return transposed(out, static_cast<std::size_t>(f.components), vertices_);
}

}  // namespace runnel
