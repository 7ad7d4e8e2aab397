// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "runnel/core/heightmap.hpp"
#include "runnel/core/parameters.hpp"
#include "runnel/core/stored_field.hpp"
#include "runnel/sph/particle_store.hpp"
#include "runnel/sph/sph_solver.hpp"

namespace runnel {

// docs/hdf5-schema.md. Bump on any incompatible change; readers refuse other versions.
// Version 3: the SPH density advances with the drift and particles touch a contact surface one
// radius above the terrain (the contacts field carries the contact state); versions 1 and 2 are
// refused with that reason.
inline constexpr std::int64_t kCheckpointSchemaVersion = 3;

// Everything an exact restart needs, and what Python users read.
struct CheckpointData {
  std::string model = "sph";
  std::string runnel_version, source_revision;
  std::string parameters_toml;  // the full parameter set
  // Terrain: float view (m), exact fixed-point state and the initial state (counts of the quantum).
  Heightmap terrain;
  double height_quantum = 1e-6;
  std::vector<std::int64_t> height_fixed, initial_fixed;
  // Particles in their current (sorted) order, with the rates of the last force pass.
  HostParticles particles;
  std::vector<float> ax, ay, az, drho, depth;
  // The state the pressure solver keeps between steps (PressureSolver::kept_fields(): dfsph's
  // pressures, the warm start of its solves); empty with wcsph and in files that have none.
  std::map<ParticleField, std::vector<float>> solver_state;
  std::uint32_t next_id = 0;
  // Clocks and counters.
  double time = 0, dt = 0;
  std::uint64_t steps = 0;
  std::uint64_t rain_spawned = 0;
  double rain_carry = 0;
  std::uint64_t rain_held_back = 0;  // drops rain.max_particles kept from falling
  std::int64_t seed = 0;
  SphCounters counters;
  // Grid models (model != "sph"): their vertex fields and named integer counters.
  std::vector<StoredField> fields;
  std::vector<std::pair<std::string, std::int64_t>> model_counters;

  // The run's initial terrain (initial_fixed in metres, on the terrain's grid): what a model is
  // rebuilt on before restore().
  Heightmap initial_terrain() const;
};

// Which run a checkpoint belongs to: a hash of the model and its parameters, less the keys that
// only say how long to run (run.steps, run.sim_time, run.iterations, run.report_every), so a
// resumed run is the same run. Written as the root attribute run_id.
std::string run_identity(const std::string& parameters_toml);
// The same, also over the initial terrain's grid and heights: a run's output folder is another
// run's when the file its terrain came from has changed content under the same name.
std::string run_identity(const std::string& parameters_toml, const Heightmap& initial_terrain);

// Writes atomically (temporary file, sync, rename): an interrupted write leaves the old file
// intact.
void write_checkpoint(const std::string& path, const CheckpointData& data);
// Reads and validates: schema version, every dataset present with consistent sizes, finite values.
// Throws an input error (exit code 2) naming the file and the problem.
CheckpointData read_checkpoint(const std::string& path);

}  // namespace runnel
