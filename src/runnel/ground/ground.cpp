// SPDX-License-Identifier: MIT
#include "runnel/ground/ground.hpp"
#include "runnel/core/text.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "runnel/compute/buffer_bytes.hpp"
#include "runnel/compute/launch.hpp"
#include "runnel/core/error.hpp"
#include "runnel/ground/ground_settings.hpp"
#include "runnel/ground/rain_mask.hpp"
#include "runnel/terrain/terrain_io.hpp"
#include "runnel/terrain/thermal.hpp"

namespace runnel {
namespace {

template <class T>
cl::Buffer device_copy(ComputeContext& compute, const std::vector<T>& values) {
  // At least one element: OpenCL refuses empty buffers (a stack without strata has no contacts).
  std::vector<T> data = values.empty() ? std::vector<T>(1, T{}) : values;
  return cl::Buffer(compute.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                    data.size() * sizeof(T), data.data());
}

template <class T>
std::vector<T> host_copy(ComputeContext& compute, cl::Buffer& buffer, std::size_t n) {
  std::vector<T> out(n);
  if (n > 0) compute.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, n * sizeof(T), out.data());
  return out;
}

// Hardness × (0 where frozen): the ground's factor per vertex on every material's erodibility.
std::vector<float> erodibility_mask(const GroundSettings& g, int nx, int ny) {
  std::vector<float> mask(static_cast<std::size_t>(nx) * ny, 1.0f);
  if (!g.hardness_mask.empty()) {
    mask = read_vertex_raster(g.hardness_mask, nx, ny, "ground.hardness_mask", [](float v) {
      return v >= 0 ? "" : "a hardness factor must be finite and ≥ 0";
    });
  }
  if (!g.frozen_mask.empty()) {
    const auto frozen = read_vertex_raster(g.frozen_mask, nx, ny, "ground.frozen_mask");
    for (std::size_t k = 0; k < mask.size(); ++k)
      if (frozen[k] != 0.0f) mask[k] = 0.0f;
  }
  return mask;
}

}  // namespace

Ground::Ground(ComputeContext& compute, const Parameters& params, DeviceTerrain& terrain,
               const Heightmap& initial, const std::vector<std::int64_t>& initial_fixed)
    : compute_(compute),
      terrain_(terrain),
      strata_(build_strata(params, initial, initial_fixed, terrain.quantum())) {
  const std::size_t n = strata_.vertices();
  const auto mask = erodibility_mask(GroundSettings::from(params), strata_.nx, strata_.ny);
  std::vector<float> erodibility;
  std::vector<std::int64_t> talus;
  for (const Material& m : strata_.materials) {
    erodibility.push_back(static_cast<float>(m.erodibility));
    talus.push_back(talus_threshold_quanta(terrain.cell(), m.talus_angle_deg, terrain.quantum()));
  }
  contacts_ = device_copy(
      compute, std::vector<std::int64_t>(strata_.contacts.begin() + n, strata_.contacts.end()));
  previous_ = device_copy(compute, initial_fixed);
  bed_.sediment = device_copy(compute, std::vector<std::int64_t>(n, 0));
  mask_ = device_copy(compute, mask);
  scenario_mask_ = mask;
  material_erodibility_ = device_copy(compute, erodibility);
  material_talus_ = device_copy(compute, talus);
  bed_.erodibility = device_copy(compute, std::vector<float>(n, 1.0f));
  bed_.rock_erodibility = device_copy(compute, std::vector<float>(n, 1.0f));
  bed_.sediment_erodibility = device_copy(compute, std::vector<float>(n, 1.0f));
  bed_.talus = device_copy(compute, std::vector<std::int64_t>(n, 0));
  exposed_ = device_copy(compute, std::vector<int>(n, 0));
  update_kernel_ = Kernel(compute, compute.program({"cl/ground.cl"}), "ground_update");
  update();
}

void Ground::update() {
  const int n = static_cast<int>(strata_.vertices());
  update_kernel_.set("height", terrain_.height_fixed())
      .set("previous", previous_)
      .set("sediment", bed_.sediment)
      .set("contacts", contacts_)
      .set("strata", strata_.strata)
      .set("n", n)
      .set("mask", mask_)
      .set("material_erodibility", material_erodibility_)
      .set("material_talus", material_talus_)
      .set("active_layer", static_cast<cl_long>(strata_.active_layer))
      .set("erodibility", bed_.erodibility)
      .set("rock_erodibility", bed_.rock_erodibility)
      .set("sediment_erodibility", bed_.sediment_erodibility)
      .set("talus", bed_.talus)
      .set("exposed", exposed_)
      .launch(round_up_work(static_cast<std::size_t>(n)), "ground.update");
}

void Ground::raise(const std::vector<std::int64_t>& quanta) {
  const std::size_t n = strata_.vertices();
  for (int l = 0; l <= strata_.strata; ++l)
    for (std::size_t k = 0; k < n; ++k) strata_.contacts[l * n + k] += quanta[k];
  if (strata_.strata > 0)
    compute_.queue().enqueueWriteBuffer(contacts_, CL_TRUE, 0, strata_.strata * n * 8,
                                        strata_.contacts.data() + n);
  auto previous = host_copy<std::int64_t>(compute_, previous_, n);
  for (std::size_t k = 0; k < n; ++k) previous[k] += quanta[k];
  compute_.queue().enqueueWriteBuffer(previous_, CL_TRUE, 0, n * 8, previous.data());
}

std::vector<float> Ground::rock_erodibility() {
  return host_copy<float>(compute_, bed_.rock_erodibility, strata_.vertices());
}

std::vector<std::int64_t> Ground::sediment() {
  return host_copy<std::int64_t>(compute_, bed_.sediment, strata_.vertices());
}

std::vector<int> Ground::exposed() {
  return host_copy<int>(compute_, exposed_, strata_.vertices());
}

std::vector<float> Ground::mask() {
  return host_copy<float>(compute_, mask_, strata_.vertices());
}

void Ground::paint_mask(const std::vector<int>& vertices, float value) {
  if (vertices.empty()) return;
  std::vector<float> m = mask();
  for (int k : vertices) m[static_cast<std::size_t>(k)] = value;
  compute_.queue().enqueueWriteBuffer(mask_, CL_TRUE, 0, m.size() * sizeof(float), m.data());
  mask_painted_ = true;
  update();  // the factors the models read follow at once
}

std::vector<StoredField> Ground::fields() {
  StoredField sediment{kGroundSediment, 1, {}, this->sediment()};
  // Contacts interleaved per vertex, (ny, nx, L + 1), as every stored field.
  const std::size_t n = strata_.vertices();
  const int c = strata_.strata + 1;
  StoredField contacts{kGroundContacts, c, {}, std::vector<std::int64_t>(n * c)};
  for (std::size_t k = 0; k < n; ++k)
    for (int l = 0; l < c; ++l) contacts.i64[k * c + l] = strata_.contact(l, k);
  StoredField thickness{kGroundThickness, std::max(strata_.strata, 1), {}, {}};
  std::vector<std::int64_t> rock = terrain_.download_fixed();
  for (std::size_t k = 0; k < n; ++k) rock[k] -= sediment.i64[k];
  const auto left = remaining_thickness(strata_, rock);
  thickness.i64.assign(n * thickness.components, 0);
  for (std::size_t k = 0; k < n; ++k)
    for (int l = 0; l < strata_.strata; ++l)
      thickness.i64[k * thickness.components + l] = left[l * n + k];
  std::vector<StoredField> out{sediment, contacts, thickness};
  if (mask_painted_) out.push_back({kGroundMask, 1, mask(), {}});
  return out;
}

void Ground::restore(const std::vector<StoredField>& fields) {
  const std::size_t n = strata_.vertices();
  bool have_sediment = false, have_contacts = false;
  std::vector<float> mask = scenario_mask_;
  mask_painted_ = false;
  for (const StoredField& f : fields) {
    if (f.name == kGroundMask && f.f32.size() == n) {
      mask = f.f32;
      mask_painted_ = true;
    }
    if (f.name == kGroundSediment && f.i64.size() == n) {
      compute_.queue().enqueueWriteBuffer(bed_.sediment, CL_TRUE, 0, n * 8, f.i64.data());
      have_sediment = true;
    } else if (f.name == kGroundContacts && f.components == strata_.strata + 1 &&
               f.i64.size() == n * f.components) {
      for (std::size_t k = 0; k < n; ++k)
        for (int l = 0; l < f.components; ++l)
          strata_.contacts[l * n + k] = f.i64[k * f.components + l];
      if (strata_.strata > 0)
        compute_.queue().enqueueWriteBuffer(contacts_, CL_TRUE, 0, strata_.strata * n * 8,
                                            strata_.contacts.data() + n);
      have_contacts = true;
    }
  }
  if (!have_sediment || !have_contacts)
    throw input_error("checkpoint: the run has layers or ground masks, but /fields/" +
                      std::string(kGroundSediment) + " or /fields/" + kGroundContacts +
                      " is missing or has another number of strata");
  compute_.queue().enqueueWriteBuffer(mask_, CL_TRUE, 0, n * sizeof(float), mask.data());
  // At a step boundary the previous heights are the heights.
  compute_.queue().enqueueCopyBuffer(terrain_.height_fixed(), previous_, 0, 0, n * 8);
  update();
}

MaterialTally Ground::tally() {
  return tally_materials(strata_, terrain_.download_fixed(), sediment());
}

JsonObject Ground::report() {
  return ground_summary(strata_, terrain_.download_fixed(), sediment(), terrain_.volume_quantum());
}

double Ground::device_bytes() const {
  return buffer_bytes({&contacts_, &previous_, &mask_, &material_erodibility_, &material_talus_,
                       &exposed_, &bed_.erodibility, &bed_.rock_erodibility,
                       &bed_.sediment_erodibility, &bed_.sediment, &bed_.talus});
}

std::unique_ptr<Ground> make_ground(ComputeContext& compute, const Parameters& params,
                                    DeviceTerrain& terrain, const Heightmap& initial,
                                    const std::vector<std::int64_t>& initial_fixed) {
  if (!has_ground(params)) return nullptr;
  return std::make_unique<Ground>(compute, params, terrain, initial, initial_fixed);
}

std::vector<float> rain_weights(const Parameters& params, int nx, int ny) {
  const std::string& path = params.text("ground.rain_mask");
  if (path.empty()) return std::vector<float>(static_cast<std::size_t>(nx) * ny, 1.0f);
  return read_vertex_raster(path, nx, ny, "ground.rain_mask", [](float v) {
    return v >= 0.0f && v <= 1.0f
               ? ""
               : "the rain mask is the fraction of the rain falling at each vertex, 0 to 1";
  });
}

cl::Buffer rain_weight_buffer(ComputeContext& compute, const Parameters& params,
                              const std::vector<float>& weights) {
  if (!has_rain_mask(params)) return placeholder_buffer(compute);
  return device_copy(compute, weights);
}

std::vector<StoredField> without_ground_fields(const std::vector<StoredField>& fields) {
  std::vector<StoredField> out;
  for (const StoredField& f : fields)
    if (f.name != kGroundSediment && f.name != kGroundContacts && f.name != kGroundThickness &&
        f.name != kGroundMask && f.name != kGroundRainMask)
      out.push_back(f);
  return out;
}

}  // namespace runnel
