// SPDX-License-Identifier: MIT
#pragma once
#include <array>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/compute/kernel.hpp"

namespace runnel {

// The particle fields, declared once. Persistent fields travel with the particle when the spatial
// hash reorders the arrays; rate fields are recomputed every step and are never reordered.
enum ParticleField : int {
  // clang-format off
  kX, kY, kZ,        // position, m
  kVx, kVy, kVz,     // velocity, m/s
  kRho,              // density, kg/m³
  kSediment,         // carried sediment, int32 count of volume quanta (erosion.height_quantum · cell²)
  kAge,              // s
  kLifespan,         // s; the particle evaporates when age exceeds it
  kContacts,         // uint32: erosion events so far (the acidity model's budget); top bit: touching
                     // the terrain at the end of the last step
  kId,               // stable id (uint32; the top bit marks a dead particle)
  kPersistentFieldCount,
  kAx = kPersistentFieldCount, kAy, kAz,  // acceleration, m/s²
  kDrho,                                  // dρ/dt, kg/m³/s
  kDepth,                                 // local water depth (m), from the force pass
  // What a pressure solver keeps between steps (PressureSolver::kept_fields): the sort carries it,
  // a checkpoint stores it.
  kSolverStateFirst,
  kKappa = kSolverStateFirst,  // dfsph: the constant-density solve's pressure κ (m²/s²), kept as
                               // κ·dt² (m²) for the next solve's warm start
  kKappaV,                     // dfsph: the divergence-free solve's κ, kept as κ·dt (m²/s)
  kFieldCount
  // clang-format on
};

struct ParticleFieldInfo {
  const char* name;
  const char* unit;
  bool is_integer;  // int32/uint32 on the device, not float
};
const ParticleFieldInfo& particle_field_info(ParticleField f);

inline constexpr std::uint32_t kDeadFlag = 0x80000000u;      // in id: removed at the next sort
inline constexpr std::uint32_t kTouchingFlag = 0x80000000u;  // in contacts: on the terrain

// Particles on the host, structure of arrays. Float fields in f[field]; the integer fields have
// their own vectors (f[kSediment], f[kContacts], f[kId] stay empty).
struct HostParticles {
  std::array<std::vector<float>, kPersistentFieldCount> f;
  std::vector<std::int32_t> sediment;  // volume quanta
  std::vector<std::uint32_t> contacts;
  std::vector<std::uint32_t> id;

  std::size_t size() const { return id.size(); }
  void resize(std::size_t n);
  // Appends one particle; sediment, age and contacts 0.
  void push(float x, float y, float z, float vx, float vy, float vz, float rho, float lifespan);
  // The 4-byte elements of one persistent field, whatever its type.
  void* data(ParticleField field);
  const void* data(ParticleField field) const;
};

// Particle state in device buffers (structure of arrays). Capacity grows on demand by a factor,
// copying device to device; particles are appended from the host without touching the others.
class ParticleStore {
 public:
  explicit ParticleStore(ComputeContext& compute, std::size_t initial_capacity = 1024);

  std::size_t size() const { return size_; }
  std::size_t capacity() const { return capacity_; }
  cl::Buffer& buffer(ParticleField f) { return current_[f]; }
  // Sets each field's buffer as the kernel argument of the field's name (particle_field_info), and
  // `n`, the live particle count, where the kernel takes it.
  void bind(Kernel& kernel, std::initializer_list<ParticleField> fields);
  // Sets each field's next-state buffer as the argument `<name>_new` (position and density only:
  // drift and continuity write them).
  void bind_new(Kernel& kernel, std::initializer_list<ParticleField> fields);
  cl::Buffer& scratch(ParticleField f) { return scratch_[new_slot(f)]; }
  // After a kernel wrote the new values of some fields: they become current.
  void swap_scratch(std::initializer_list<ParticleField> fields);
  // Per-particle temporaries of a pass, one float each, valid until the next sort.
  static constexpr int kSpareCount = 7;
  cl::Buffer& spare(int k) { return scratch_[kNewFieldCount + k]; }
  // The hash's reorder, a few fields at a time through the next-state and spare buffers, which
  // hold nothing during the sort: gather into temporary(k), then adopt_temporary(f, k) makes it the
  // field (and the field's old buffer that temporary). So the reorder needs no second copy of
  // every field.
  static constexpr int kTemporaryCount = 11;
  cl::Buffer& temporary(int k) { return scratch_[k]; }
  void adopt_temporary(ParticleField f, int k) { std::swap(current_[f], scratch_[k]); }
  // Drops the particles past n (dead ones, sorted to the end).
  void truncate(std::size_t n);

  // Makes room for k particles at the end, to be written by a kernel (rain): grows the capacity,
  // zeroes their rates, reserves k ids. Returns the index of the first new particle.
  std::size_t extend(std::size_t k);
  // Appends particles; ids are assigned here, consecutively from the next free id. Returns the
  // first id.
  std::uint32_t append(HostParticles particles);
  std::uint32_t next_id() const { return next_id_; }
  void set_next_id(std::uint32_t id) { next_id_ = id; }

  // Downloads every persistent field (blocking).
  HostParticles download();
  // Downloads one field of the live particles as floats (ids as their float value is not useful:
  // use download()).
  std::vector<float> read_field(ParticleField f);
  // Writes one float field of the live particles (checkpoint restore of the rates).
  void upload_field(ParticleField f, const std::vector<float>& values);
  // Replaces the whole state (checkpoint restore); ids are kept as given.
  void upload(const HostParticles& particles);

  // Device bytes per particle of capacity: current + scratch persistent fields, rates, sort keys.
  static std::size_t bytes_per_particle();

 private:
  void grow_to(std::size_t needed);
  ComputeContext& compute_;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
  std::uint32_t next_id_ = 0;
  std::array<cl::Buffer, kFieldCount> current_;
  static constexpr int kNewFieldCount = 4;  // x, y, z, rho
  static int new_slot(ParticleField f);
  // The next state of x, y, z, rho, then the spares: 11 words, so that with the 19 fields and the
  // hash's 4 a particle of capacity holds 34 words (136 bytes).
  std::array<cl::Buffer, kNewFieldCount + kSpareCount> scratch_;
  static_assert(kTemporaryCount == kNewFieldCount + kSpareCount);
};

}  // namespace runnel
