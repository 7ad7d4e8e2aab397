// SPDX-License-Identifier: MIT
#include "runnel/sph/particle_store.hpp"

#include <algorithm>

#include "runnel/core/error.hpp"

namespace runnel {
namespace {

constexpr double kGrowthFactor = 1.5;  // amortised growth; keeps spare capacity below 50 %

const ParticleFieldInfo kFieldInfo[kFieldCount] = {
    {"x", "m", false},           {"y", "m", false},
    {"z", "m", false},           {"vx", "m/s", false},
    {"vy", "m/s", false},        {"vz", "m/s", false},
    {"rho", "kg/m^3", false},    {"sediment", "quanta", true},
    {"age", "s", false},         {"lifespan", "s", false},
    {"contacts", "1", true},     {"id", "1", true},
    {"ax", "m/s^2", false},      {"ay", "m/s^2", false},
    {"az", "m/s^2", false},      {"drho", "kg/m^3/s", false},
    {"depth", "m", false},       {"kappa", "m^2", false},
    {"kappa_v", "m^2/s", false},
};
static_assert(sizeof(kFieldInfo) / sizeof(kFieldInfo[0]) == kFieldCount);

bool is_float_field(int k) {
  return !kFieldInfo[k].is_integer;
}

}  // namespace

const ParticleFieldInfo& particle_field_info(ParticleField f) {
  return kFieldInfo[f];
}

void HostParticles::resize(std::size_t n) {
  for (int k = 0; k < kPersistentFieldCount; ++k) {
    if (is_float_field(k)) f[k].resize(n, 0.0f);
  }
  sediment.resize(n, 0);
  contacts.resize(n, 0);
  id.resize(n, 0);
}

void* HostParticles::data(ParticleField field) {
  return const_cast<void*>(static_cast<const HostParticles*>(this)->data(field));
}

const void* HostParticles::data(ParticleField field) const {
  switch (field) {
    case kSediment:
      return sediment.data();
    case kContacts:
      return contacts.data();
    case kId:
      return id.data();
    default:
      return f[field].data();
  }
}

void HostParticles::push(float x, float y, float z, float vx, float vy, float vz, float rho,
                         float lifespan) {
  const float values[kPersistentFieldCount] = {x,   y,    z,    vx,       vy,   vz,
                                               rho, 0.0f, 0.0f, lifespan, 0.0f, 0.0f};
  for (int k = 0; k < kPersistentFieldCount; ++k) {
    if (is_float_field(k)) f[k].push_back(values[k]);
  }
  sediment.push_back(0);
  contacts.push_back(0);
  id.push_back(0);
}

ParticleStore::ParticleStore(ComputeContext& compute, std::size_t initial_capacity)
    : compute_(compute) {
  grow_to(std::max<std::size_t>(initial_capacity, 64));
}

std::size_t ParticleStore::bytes_per_particle() {
  // current (all fields) + next state and spares + the hash's keys and values, double-buffered.
  return 4 * (kFieldCount + kNewFieldCount + kSpareCount + 4);
}

int ParticleStore::new_slot(ParticleField f) {
  switch (f) {
    case kX:
      return 0;
    case kY:
      return 1;
    case kZ:
      return 2;
    case kRho:
      return 3;
    default:
      throw runtime_error(std::string("particle field ") + kFieldInfo[f].name +
                          " has no next-state buffer");
  }
}

void ParticleStore::grow_to(std::size_t needed) {
  if (needed <= capacity_) return;
  const std::size_t new_capacity =
      std::max(needed, static_cast<std::size_t>(static_cast<double>(capacity_) * kGrowthFactor));
  if (new_capacity > 0x7fffffffu) throw runtime_error("particle capacity exceeds 2^31 particles");
  auto& ctx = compute_.context();
  for (int k = 0; k < kFieldCount; ++k) {
    cl::Buffer grown(ctx, CL_MEM_READ_WRITE, new_capacity * 4);
    if (size_ > 0) compute_.queue().enqueueCopyBuffer(current_[k], grown, 0, 0, size_ * 4);
    current_[k] = grown;
  }
  for (auto& b : scratch_) b = cl::Buffer(ctx, CL_MEM_READ_WRITE, new_capacity * 4);
  capacity_ = new_capacity;
}

void ParticleStore::bind(Kernel& kernel, std::initializer_list<ParticleField> fields) {
  for (ParticleField f : fields) kernel.set(kFieldInfo[f].name, current_[f]);
  if (kernel.has("n")) kernel.set("n", static_cast<cl_uint>(size_));
}

void ParticleStore::bind_new(Kernel& kernel, std::initializer_list<ParticleField> fields) {
  for (ParticleField f : fields)
    kernel.set(std::string(kFieldInfo[f].name) + "_new", scratch_[new_slot(f)]);
}

void ParticleStore::swap_scratch(std::initializer_list<ParticleField> fields) {
  for (ParticleField f : fields) std::swap(current_[f], scratch_[new_slot(f)]);
}

void ParticleStore::truncate(std::size_t n) {
  size_ = std::min(size_, n);
}

std::uint32_t ParticleStore::append(HostParticles p) {
  const std::size_t k = p.size();
  const std::uint32_t first = next_id_;
  if (k == 0) return first;
  if (static_cast<std::uint64_t>(next_id_) + k >= kDeadFlag)
    throw runtime_error("particle ids exhausted (2^31)");
  for (std::size_t i = 0; i < k; ++i) p.id[i] = next_id_ + static_cast<std::uint32_t>(i);
  next_id_ += static_cast<std::uint32_t>(k);
  grow_to(size_ + k);
  auto& q = compute_.queue();
  for (int f = 0; f < kPersistentFieldCount; ++f) {
    q.enqueueWriteBuffer(current_[f], CL_TRUE, size_ * 4, k * 4,
                         p.data(static_cast<ParticleField>(f)));
  }
  // Rates start at zero until the first force evaluation.
  const float zero = 0.0f;
  for (int f = kPersistentFieldCount; f < kFieldCount; ++f)
    q.enqueueFillBuffer(current_[f], zero, size_ * 4, k * 4);
  size_ += k;
  return first;
}

std::size_t ParticleStore::extend(std::size_t k) {
  const std::size_t first = size_;
  if (k == 0) return first;
  if (static_cast<std::uint64_t>(next_id_) + k >= kDeadFlag)
    throw runtime_error("particle ids exhausted (2^31)");
  grow_to(size_ + k);
  const float zero = 0.0f;
  for (int f = kPersistentFieldCount; f < kFieldCount; ++f) {
    compute_.queue().enqueueFillBuffer(current_[f], zero, size_ * 4, k * 4);
  }
  next_id_ += static_cast<std::uint32_t>(k);
  size_ += k;
  return first;
}

HostParticles ParticleStore::download() {
  HostParticles p;
  p.resize(size_);
  if (size_ == 0) return p;
  auto& q = compute_.queue();
  for (int f = 0; f < kPersistentFieldCount; ++f) {
    q.enqueueReadBuffer(current_[f], CL_TRUE, 0, size_ * 4, p.data(static_cast<ParticleField>(f)));
  }
  return p;
}

std::vector<float> ParticleStore::read_field(ParticleField f) {
  std::vector<float> out(size_);
  if (size_ > 0) compute_.queue().enqueueReadBuffer(current_[f], CL_TRUE, 0, size_ * 4, out.data());
  return out;
}

void ParticleStore::upload_field(ParticleField f, const std::vector<float>& values) {
  if (values.size() != size_) throw runtime_error("upload_field: size mismatch");
  if (size_ > 0)
    compute_.queue().enqueueWriteBuffer(current_[f], CL_TRUE, 0, size_ * 4, values.data());
}

void ParticleStore::upload(const HostParticles& p) {
  size_ = 0;
  grow_to(p.size());
  auto& q = compute_.queue();
  for (int f = 0; f < kPersistentFieldCount && p.size() > 0; ++f) {
    q.enqueueWriteBuffer(current_[f], CL_TRUE, 0, p.size() * 4,
                         p.data(static_cast<ParticleField>(f)));
  }
  size_ = p.size();
}

}  // namespace runnel
