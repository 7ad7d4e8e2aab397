// SPDX-License-Identifier: MIT
// HDF5 checkpoints (docs/hdf5-schema.md).
#include "runnel/models/checkpoint.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "runnel/core/error.hpp"
#include "runnel/io/atomic_file.hpp"
#include "runnel/io/crash_isolated_read.hpp"
#include "runnel/io/georeference_h5.hpp"
#include "runnel/io/hdf5_file.hpp"
#include "runnel/models/fields.hpp"
#include "runnel/terrain/terrain_io.hpp"

namespace runnel {

// The longest text kept as an attribute (HDF5's limit is 64 KiB with the object's other
// attributes).
constexpr std::size_t kLargestTextAttribute = 60000;
namespace {

// Float particle fields stored under /particles, in ParticleField order.
const ParticleField kFloatFields[] = {kX, kY, kZ, kVx, kVy, kVz, kRho, kAge, kLifespan};

std::string dataset_path(const char* group, const char* name) {
  return std::string("/") + group + "/" + name;
}

void require_finite(const std::string& path, const std::string& name,
                    const std::vector<float>& values) {
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (!std::isfinite(values[k])) {
      throw input_error(path + ": " + name + "[" + std::to_string(k) + "] is not a finite number");
    }
  }
}

std::vector<std::string> split_names(const std::string& list) {
  std::vector<std::string> names;
  std::size_t start = 0;
  while (start < list.size()) {
    const std::size_t end = std::min(list.find(',', start), list.size());
    if (end > start) names.push_back(list.substr(start, end - start));
    start = end + 1;
  }
  return names;
}

// Version 2: the grid models' fields (/fields/NAME, float32 or int64) and counters.
void read_model_state(const H5File& f, const std::string& path, const std::vector<hsize_t>& grid,
                      CheckpointData& d) {
  for (const std::string& name : split_names(f.read_string_attribute("/state", "counters"))) {
    d.model_counters.emplace_back(name, f.read_int_attribute("/state", "counter_" + name));
  }
  for (const std::string& name : split_names(f.read_string_attribute("/fields", "names"))) {
    const std::string dataset = "/fields/" + name;
    const std::vector<hsize_t> dims = f.dims(dataset);
    if (dims.size() < 2 || dims.size() > 3 || dims[0] != grid[0] || dims[1] != grid[1])
      throw input_error(path + ": " + dataset + " does not match the terrain grid");
    StoredField field;
    field.name = name;
    field.components = dims.size() == 3 ? static_cast<int>(dims[2]) : 1;
    if (f.is_integer(dataset)) {
      field.i64 = f.read_int64(dataset, dims);
    } else {
      field.f32 = f.read_float(dataset, dims);
      require_finite(path, dataset, field.f32);
    }
    d.fields.push_back(std::move(field));
  }
}

// FNV-1a over the bytes of every value a restart reads, in one fixed order: written as the root
// attribute `digest` and checked on read, so a flipped byte anywhere in the data is a refusal, not
// a different run.
class Digest {
 public:
  template <typename T>
  Digest& add(const std::vector<T>& values) {
    return bytes(values.data(), values.size() * sizeof(T));
  }
  template <typename T>
  Digest& add(const T& value) {
    return bytes(&value, sizeof value);
  }
  Digest& add(const std::string& text) { return bytes(text.data(), text.size()); }
  std::string hex() const {
    char out[17];
    std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(hash_));
    return out;
  }

 private:
  Digest& bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < n; ++k) hash_ = (hash_ ^ p[k]) * 0x100000001b3ULL;
    hash_ = (hash_ ^ 0xff) * 0x100000001b3ULL;  // a separator, so ("ab", "c") ≠ ("a", "bc")
    return *this;
  }
  std::uint64_t hash_ = 0xcbf29ce484222325ULL;
};

std::string digest_of(const CheckpointData& d) {
  Digest g;
  g.add(d.model).add(d.parameters_toml).add(d.terrain.h).add(d.terrain.cell);
  g.add(d.terrain.origin_x).add(d.terrain.origin_z).add(d.height_quantum);
  // Only when present, so files written before georeferencing still verify.
  if (!d.terrain.georef.crs_wkt.empty()) g.add(d.terrain.georef.crs_wkt);
  if (d.terrain.georef.nodata) g.add(*d.terrain.georef.nodata);
  g.add(d.height_fixed).add(d.initial_fixed);
  for (const auto& field : d.particles.f) g.add(field);
  g.add(d.particles.sediment).add(d.particles.contacts).add(d.particles.id);
  g.add(d.ax).add(d.ay).add(d.az).add(d.drho).add(d.depth).add(d.next_id);
  // Only when present, so files of the weakly compressible solver verify as before.
  for (const auto& [field, values] : d.solver_state) g.add(values);
  g.add(d.time).add(d.dt).add(d.steps).add(d.rain_spawned).add(d.rain_carry).add(d.seed);
  // Only when some rain was held back, so files without the count verify as before.
  if (d.rain_held_back > 0) g.add(d.rain_held_back);
  const SphCounters& c = d.counters;
  for (long long v : {c.surface_projections, c.outflow_particles, c.collisions, c.outflow_sediment,
                      c.evaporated_particles, c.lost_sediment})
    g.add(v);
  for (const auto& f : d.fields) g.add(f.name).add(f.components).add(f.f32).add(f.i64);
  for (const auto& [name, value] : d.model_counters) g.add(name).add(value);
  return g.hex();
}

// What the writer guarantees, checked on read: one line naming the file and the field.
void check_invariants(const std::string& path, const CheckpointData& d) {
  auto refuse = [&](const std::string& what) {
    throw input_error(path + ": " + what + " (the file is damaged or was not written by runnel)");
  };
  if (d.parameters_toml.empty()) refuse("@parameters_toml is empty");
  if (!(d.time >= 0) || d.steps > (std::uint64_t{1} << 62))
    refuse("/state time or steps out of range");
  if (d.rain_spawned > (std::uint64_t{1} << 62)) refuse("/state@rain_spawned is negative");
  if (d.rain_held_back > (std::uint64_t{1} << 62)) refuse("/state@rain_held_back is negative");
  if (!(d.rain_carry >= 0 && d.rain_carry < 1)) refuse("/state@rain_carry is not in [0, 1)");
  if (d.seed < 0) refuse("/state@seed is negative");
  const SphCounters& c = d.counters;
  for (long long v : {c.surface_projections, c.outflow_particles, c.collisions, c.outflow_sediment,
                      c.evaporated_particles, c.lost_sediment})
    if (v < 0) refuse("/state/counters holds a negative count");
  for (const auto& [name, value] : d.model_counters)
    if (value < 0) refuse("/state@counter_" + name + " is negative");
  for (std::size_t k = 0; k < d.height_fixed.size(); ++k) {
    const double exact = static_cast<double>(d.height_fixed[k]) * d.height_quantum;
    if (!(std::fabs(d.terrain.h[k] - exact) <= 1e-6 * std::fabs(exact) + 2 * d.height_quantum))
      refuse("/terrain/height disagrees with /terrain/height_fixed at vertex " + std::to_string(k));
  }
  for (std::size_t k = 0; k < d.particles.size(); ++k) {
    if (d.particles.sediment[k] < 0) refuse("/particles/sediment is negative");
    if ((d.particles.id[k] & ~kDeadFlag) >= d.next_id) refuse("/particles/id is not below next_id");
  }
  for (const auto& field : d.fields)
    for (std::int64_t v : field.i64)
      if (v < 0 && (field.name == kSedimentSuspended || field.name == "ground__sediment_thickness"))
        refuse("/fields/" + field.name + " is negative");
}

}  // namespace

Heightmap CheckpointData::initial_terrain() const {
  Heightmap initial = terrain;
  for (std::size_t k = 0; k < initial.size(); ++k)
    initial.h[k] = static_cast<float>(static_cast<double>(initial_fixed[k]) * height_quantum);
  return initial;
}

namespace {

// /terrain: the heights (float and fixed point), the initial ones, the erosion maps and the grid's
// georeferencing.
void write_terrain_group(H5File& f, const CheckpointData& d) {
  const Heightmap& t = d.terrain;
  const std::vector<hsize_t> grid = {static_cast<hsize_t>(t.ny), static_cast<hsize_t>(t.nx)};
  f.create_group("/terrain");
  f.write("/terrain/height", t.h, grid);
  f.write("/terrain/height_fixed", d.height_fixed, grid);
  f.write("/terrain/initial_fixed", d.initial_fixed, grid);
  std::vector<float> eroded(t.size()), deposited(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double change =
        static_cast<double>(d.height_fixed[k] - d.initial_fixed[k]) * d.height_quantum;
    eroded[k] = static_cast<float>(std::max(0.0, -change));
    deposited[k] = static_cast<float>(std::max(0.0, change));
  }
  f.write("/terrain/eroded", eroded, grid);
  f.write("/terrain/deposited", deposited, grid);
  f.attribute("/terrain", "cell", t.cell);
  f.attribute("/terrain", "origin_x", t.origin_x);
  f.attribute("/terrain", "origin_z", t.origin_z);
  // The source's georeferencing (absent when it had none): the CRS, its NODATA value and holes.
  write_georeference(f, "/terrain", t);
  f.attribute("/terrain", "height_quantum", d.height_quantum);
}

// /particles: every field of every particle, and the rates a restart needs.
void write_particles_group(H5File& f, const CheckpointData& d) {
  const hsize_t n = d.particles.size();
  f.create_group("/particles");
  for (ParticleField field : kFloatFields) {
    f.write(dataset_path("particles", particle_field_info(field).name), d.particles.f[field], {n});
  }
  f.write("/particles/sediment", d.particles.sediment, {n});
  f.write("/particles/contacts", d.particles.contacts, {n});
  f.write("/particles/id", d.particles.id, {n});
  f.write("/particles/ax", d.ax, {n});
  f.write("/particles/ay", d.ay, {n});
  f.write("/particles/az", d.az, {n});
  f.write("/particles/drho", d.drho, {n});
  f.write("/particles/depth", d.depth, {n});
  for (const auto& [field, values] : d.solver_state)
    f.write(dataset_path("particles", particle_field_info(field).name), values, {n});
  f.attribute("/particles", "count", static_cast<std::int64_t>(n));
  f.attribute("/particles", "next_id", static_cast<std::int64_t>(d.next_id));
  f.attribute("/particles", "sediment_quantum_m3",
              d.height_quantum * d.terrain.cell * d.terrain.cell);
}

// /state: the clock, the rain's counters, the seed and the model's counters.
void write_state_group(H5File& f, const CheckpointData& d) {
  f.create_group("/state");
  f.attribute("/state", "time", d.time);
  f.attribute("/state", "dt", d.dt);
  f.attribute("/state", "steps", static_cast<std::int64_t>(d.steps));
  f.attribute("/state", "rain_spawned", static_cast<std::int64_t>(d.rain_spawned));
  f.attribute("/state", "rain_carry", d.rain_carry);
  f.attribute("/state", "rain_held_back", static_cast<std::int64_t>(d.rain_held_back));
  f.attribute("/state", "seed", d.seed);
  const SphCounters& c = d.counters;
  f.write("/state/counters",
          std::vector<std::int64_t>{c.surface_projections, c.outflow_particles, c.collisions,
                                    c.outflow_sediment, c.evaporated_particles, c.lost_sediment},
          {6});
  std::string counter_names;
  for (auto& [name, value] : d.model_counters) {
    counter_names += (counter_names.empty() ? "" : ",") + name;
    f.attribute("/state", "counter_" + name, value);
  }
  f.attribute("/state", "counters", counter_names);
}

// /fields: the grid models' fields, by their dictionary names.
void write_fields_group(H5File& f, const CheckpointData& d) {
  const auto ny = static_cast<hsize_t>(d.terrain.ny), nx = static_cast<hsize_t>(d.terrain.nx);
  f.create_group("/fields");
  std::string field_names;
  for (const StoredField& field : d.fields) {
    field_names += (field_names.empty() ? "" : ",") + field.name;
    const std::vector<hsize_t> dims =
        field.components > 1 ? std::vector<hsize_t>{ny, nx, static_cast<hsize_t>(field.components)}
                             : std::vector<hsize_t>{ny, nx};
    const std::string name = "/fields/" + field.name;
    if (!field.i64.empty())
      f.write(name, field.i64, dims);
    else
      f.write(name, field.f32, dims);
  }
  f.attribute("/fields", "names", field_names);
}

}  // namespace

void write_checkpoint(const std::string& path, const CheckpointData& d) {
  write_path_atomically(path, [&](const std::string& temporary) {
    H5File f = H5File::create(temporary);
    f.attribute("/", "schema_version", kCheckpointSchemaVersion);
    f.attribute("/", "runnel_version", d.runnel_version);
    f.attribute("/", "source_revision", d.source_revision);
    f.attribute("/", "model", d.model);
    // An attribute holds 64 KiB: a larger parameter set (thousands of gauges or bodies) goes in
    // a dataset of that name instead.
    if (d.parameters_toml.size() <= kLargestTextAttribute)
      f.attribute("/", "parameters_toml", d.parameters_toml);
    else
      f.write_text("/parameters_toml", d.parameters_toml);
    f.attribute("/", "run_id", run_identity(d.parameters_toml));
    f.attribute("/", "digest", digest_of(d));
    write_terrain_group(f, d);
    write_particles_group(f, d);
    write_state_group(f, d);
    write_fields_group(f, d);
    f.flush();
  });
}

std::string run_identity(const std::string& parameters_toml, const Heightmap& initial_terrain) {
  Digest id;
  id.add(run_identity(parameters_toml))
      .add(initial_terrain.nx)
      .add(initial_terrain.ny)
      .add(initial_terrain.cell)
      .add(initial_terrain.h);
  return id.hex();
}

std::string run_identity(const std::string& parameters_toml) {
  Digest id;
  std::istringstream lines(parameters_toml);
  for (std::string line; std::getline(lines, line);) {
    bool length_only = false;
    for (const char* key : {"steps =", "sim_time =", "iterations =", "report_every ="})
      length_only = length_only || line.rfind(key, 0) == 0;
    if (!length_only) id.add(line);
  }
  return id.hex();
}

namespace {
CheckpointData read_checkpoint_contents(const std::string& path);
}

// libhdf5 1.10.8 crashes on some damaged files instead of reporting them (SIGFPE in H5Dopen2 on a
// chunk dimension of 0, found by fuzz.checkpoint), so the whole read runs once in a child first.
CheckpointData read_checkpoint(const std::string& path) {
  refuse_if_reading_crashes(path, [&] { read_checkpoint_contents(path); });
  return read_checkpoint_contents(path);
}

namespace {

// /terrain, checked as it is read; returns its grid's dimensions (ny, nx).
std::vector<hsize_t> read_terrain_group(const H5File& f, const std::string& path,
                                        CheckpointData& d) {
  const std::vector<hsize_t> grid = f.dims("/terrain/height");
  if (grid.size() != 2 || grid[0] < 2 || grid[1] < 2)
    throw input_error(path + ": /terrain/height is not a 2-D grid");
  check_terrain_size(path, static_cast<long long>(grid[1]), static_cast<long long>(grid[0]));
  d.terrain = Heightmap(static_cast<int>(grid[1]), static_cast<int>(grid[0]),
                        f.read_double_attribute("/terrain", "cell"));
  if (!(d.terrain.cell > 0)) throw input_error(path + ": /terrain@cell is not positive");
  d.terrain.h = f.read_float("/terrain/height", grid);
  require_finite(path, "/terrain/height", d.terrain.h);
  d.terrain.origin_x = f.read_double_attribute("/terrain", "origin_x");
  d.terrain.origin_z = f.read_double_attribute("/terrain", "origin_z");
  read_georeference(f, path, "/terrain", d.terrain);
  d.height_quantum = f.read_double_attribute("/terrain", "height_quantum");
  if (!(d.height_quantum > 0))
    throw input_error(path + ": /terrain@height_quantum is not positive");
  d.height_fixed = f.read_int64("/terrain/height_fixed", grid);
  d.initial_fixed = f.read_int64("/terrain/initial_fixed", grid);

  return grid;
}

// /particles, the count checked against the datasets before anything is allocated.
void read_particles_group(const H5File& f, const std::string& path, CheckpointData& d) {
  const std::int64_t count = f.read_int_attribute("/particles", "count");
  if (count < 0) throw input_error(path + ": /particles@count is negative");
  const std::vector<hsize_t> n = {static_cast<hsize_t>(count)};
  // The count must be what the datasets hold before anything is allocated for it.
  if (f.dims("/particles/x") != n)
    throw input_error(path + ": /particles@count disagrees with the size of /particles/x");
  d.particles.resize(static_cast<std::size_t>(count));
  for (ParticleField field : kFloatFields) {
    const std::string name = dataset_path("particles", particle_field_info(field).name);
    d.particles.f[field] = f.read_float(name, n);
    require_finite(path, name, d.particles.f[field]);
  }
  d.particles.sediment = f.read_int32("/particles/sediment", n);
  d.particles.contacts = f.read_uint32("/particles/contacts", n);
  d.particles.id = f.read_uint32("/particles/id", n);
  d.ax = f.read_float("/particles/ax", n);
  d.ay = f.read_float("/particles/ay", n);
  d.az = f.read_float("/particles/az", n);
  d.drho = f.read_float("/particles/drho", n);
  d.depth = f.read_float("/particles/depth", n);
  for (int k = kSolverStateFirst; k < kFieldCount; ++k) {
    const auto field = static_cast<ParticleField>(k);
    const std::string name = dataset_path("particles", particle_field_info(field).name);
    if (!f.exists(name)) continue;
    d.solver_state[field] = f.read_float(name, n);
    require_finite(path, name, d.solver_state[field]);
  }
  for (auto* rates : {&d.ax, &d.ay, &d.az, &d.drho})
    require_finite(path, "/particles rates", *rates);
  d.next_id = static_cast<std::uint32_t>(f.read_int_attribute("/particles", "next_id"));
}

// /state: the clock, the rain's counters, the seed and the counters.
void read_state_group(const H5File& f, const std::string& path, CheckpointData& d) {
  d.time = f.read_double_attribute("/state", "time");
  d.dt = f.read_double_attribute("/state", "dt");
  if (!std::isfinite(d.time) || !(d.dt > 0) || !std::isfinite(d.dt))
    throw input_error(path + ": /state time or dt is invalid");
  const std::int64_t steps = f.read_int_attribute("/state", "steps");
  const std::int64_t spawned = f.read_int_attribute("/state", "rain_spawned");
  if (steps < 0 || spawned < 0)
    throw input_error(path + ": /state@steps or @rain_spawned is negative");
  d.steps = static_cast<std::uint64_t>(steps);
  d.rain_spawned = static_cast<std::uint64_t>(spawned);
  d.rain_carry = f.read_double_attribute("/state", "rain_carry");
  if (f.has_attribute("/state", "rain_held_back"))
    d.rain_held_back = static_cast<std::uint64_t>(f.read_int_attribute("/state", "rain_held_back"));
  d.seed = f.read_int_attribute("/state", "seed");
  const auto c = f.read_int64("/state/counters", {6});
  d.counters = {c[0], c[1], c[2], c[3], c[4], c[5]};
}

CheckpointData read_checkpoint_contents(const std::string& path) {
  const H5File f = H5File::open_read(path);
  if (!f.exists("/terrain") && !f.exists("/particles")) {
    throw input_error(path + ": not a runnel checkpoint (no /terrain or /particles)");
  }
  const std::int64_t version = f.read_int_attribute("/", "schema_version");
  if (version == 1 || version == 2) {
    throw input_error(path + ": checkpoint schema version " + std::to_string(version) +
                      " was written before the SPH time integration and terrain contact changed "
                      "(schema 3): it cannot continue exactly here; resume it with the runnel that "
                      "wrote it, or start the run again");
  }
  if (version != kCheckpointSchemaVersion) {
    throw input_error(path + ": checkpoint schema version " + std::to_string(version) +
                      ", this runnel reads version " + std::to_string(kCheckpointSchemaVersion));
  }
  CheckpointData d;
  d.model = f.read_string_attribute("/", "model");
  d.runnel_version = f.read_string_attribute("/", "runnel_version");
  d.source_revision = f.read_string_attribute("/", "source_revision");
  d.parameters_toml = f.has_attribute("/", "parameters_toml")
                          ? f.read_string_attribute("/", "parameters_toml")
                          : f.read_text("/parameters_toml");

  const std::vector<hsize_t> grid = read_terrain_group(f, path, d);
  read_particles_group(f, path, d);
  read_state_group(f, path, d);
  read_model_state(f, path, grid, d);
  check_invariants(path, d);
  // A file that cannot be verified is not resumed: without the digest an edited velocity, seed
  // or model label would be taken as the run's own.
  if (!f.has_attribute("/", "digest"))
    throw input_error(path +
                      ": has no digest, so its data cannot be verified (a checkpoint of an "
                      "older runnel, or edited by another program)");
  if (f.read_string_attribute("/", "digest") != digest_of(d)) {
    throw input_error(path + ": the data do not match the file's digest (the file is damaged)");
  }
  return d;
}

}  // namespace

}  // namespace runnel
