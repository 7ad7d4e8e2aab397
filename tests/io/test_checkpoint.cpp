// SPDX-License-Identifier: MIT
// HDF5 checkpoints: every dataset round-trips, a resumed run equals an uninterrupted one bit for
// bit, bad files are refused with one line, writes never leave a half-written file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>

#include "runnel/core/error.hpp"
#include "runnel/io/atomic_file.hpp"
#include "runnel/io/hdf5_file.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/models/sph_model.hpp"
#include "runnel/models/sph_simulation.hpp"
#include "runnel/terrain/generators.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

Parameters rainy(const std::string& solver = "wcsph", bool above_water = false) {
  Parameters p = default_parameters();
  p.set("sph.solver", solver);
  p.set("rain.above_water", above_water);
  p.set("rain.rate", 3000.0);
  p.set("rain.lifespan", 0.5);
  p.set("thermal.interval", 0.02);
  p.set("run.seed", static_cast<std::int64_t>(12));
  p.set("terrain.set.relief", 0.3);
  return p;
}

std::unique_ptr<Simulation> fresh(const std::string& solver = "wcsph", bool above_water = false) {
  return std::make_unique<Simulation>(compute(), rainy(solver, above_water),
                                      generate_terrain("fbm", 41, 33, 1.0, 5, {{"relief", 0.3}}));
}

void expect_same_state(Simulation& a, Simulation& b) {
  EXPECT_EQ(a.steps(), b.steps());
  EXPECT_EQ(a.time(), b.time());
  EXPECT_EQ(a.dt(), b.dt());
  EXPECT_EQ(a.solver().terrain().download_fixed(), b.solver().terrain().download_fixed());
  const HostParticles p = a.solver().particles().download(), q = b.solver().particles().download();
  ASSERT_EQ(p.size(), q.size());
  for (int f = 0; f < kPersistentFieldCount; ++f) {
    const auto field = static_cast<ParticleField>(f);
    EXPECT_EQ(0, std::memcmp(p.data(field), q.data(field), p.size() * 4))
        << particle_field_info(field).name;
  }
  const SphCounters c = a.counters(), d = b.counters();
  EXPECT_EQ(c.outflow_sediment, d.outflow_sediment);
  EXPECT_EQ(c.evaporated_particles, d.evaporated_particles);
}

TEST(Checkpoint, EveryDatasetRoundTrips) {
  test::ScratchDir dir;
  auto sim = fresh();
  for (int k = 0; k < 150; ++k) sim->step();
  const CheckpointData d = sim->checkpoint();
  ASSERT_GT(d.particles.size(), 50u);
  write_checkpoint(dir.path("c.h5"), d);
  const CheckpointData r = read_checkpoint(dir.path("c.h5"));
  EXPECT_EQ(r.model, "sph");
  EXPECT_EQ(r.parameters_toml, d.parameters_toml);
  EXPECT_EQ(r.terrain.h, d.terrain.h);
  EXPECT_EQ(r.terrain.cell, d.terrain.cell);
  EXPECT_EQ(r.height_fixed, d.height_fixed);
  EXPECT_EQ(r.initial_fixed, d.initial_fixed);
  EXPECT_EQ(r.height_quantum, d.height_quantum);
  for (int f = 0; f < kPersistentFieldCount; ++f) {
    const auto field = static_cast<ParticleField>(f);
    EXPECT_EQ(0,
              std::memcmp(r.particles.data(field), d.particles.data(field), d.particles.size() * 4))
        << particle_field_info(field).name;
  }
  EXPECT_EQ(r.ax, d.ax);
  EXPECT_EQ(r.drho, d.drho);
  EXPECT_EQ(r.depth, d.depth);
  EXPECT_EQ(r.next_id, d.next_id);
  EXPECT_EQ(r.time, d.time);
  EXPECT_EQ(r.dt, d.dt);
  EXPECT_EQ(r.steps, d.steps);
  EXPECT_EQ(r.rain_spawned, d.rain_spawned);
  EXPECT_EQ(r.rain_carry, d.rain_carry);
  EXPECT_EQ(r.counters.collisions, d.counters.collisions);
  EXPECT_EQ(r.counters.lost_sediment, d.counters.lost_sediment);
  // The parameters read back to the same values.
  const Parameters p = make_model_from_checkpoint(compute(), r)->parameters();
  EXPECT_EQ(p.values(), sim->parameters().values());
  EXPECT_EQ(p.generator_values(), sim->parameters().generator_values());
}

// A run of `steps` steps, and the same run stopped halfway, checkpointed and resumed through the
// Model interface (as runnel resume and the viewer do): the two end in the same state.
void expect_exact_resume(const std::string& solver, int steps, bool above_water = false) {
  test::ScratchDir dir;
  auto straight = fresh(solver, above_water);
  for (int k = 0; k < steps; ++k) straight->step();
  auto first_half = fresh(solver, above_water);
  for (int k = 0; k < steps / 2; ++k) first_half->step();
  write_checkpoint(dir.path("half.h5"), first_half->checkpoint());
  first_half.reset();
  const CheckpointData d = read_checkpoint(dir.path("half.h5"));
  EXPECT_NE(d.parameters_toml.find(solver), std::string::npos);  // the file records its solver
  if (solver ==
      "dfsph") {  // and the pressures its solves start from (some water is under pressure)
    const std::vector<float>& kappa = d.solver_state.at(kKappa);
    ASSERT_EQ(kappa.size(), d.particles.size());
    EXPECT_GT(std::count_if(kappa.begin(), kappa.end(), [](float k) { return k > 0; }), 0);
  }
  auto model = make_model_from_checkpoint(compute(), d);
  for (int k = 0; k < steps - steps / 2; ++k) model->step();
  expect_same_state(*straight, static_cast<SphModel&>(*model).simulation());
  EXPECT_EQ(model->mass_balance().residual_quanta, 0);
}

TEST(Checkpoint, ResumedRunEqualsAnUninterruptedOne) {
  expect_exact_resume("wcsph", 240);
}

// Rain above the water reads the water field of the step before; the exchange interval
// (erosion.exchange_interval, 0.01 s: every fifth step or so of wcsph) leaves the particles' depth
// to the exchanges' steps, but the field is kept current, and a resumed run measures it afresh
// from the same positions.
TEST(Checkpoint, ResumedRunWithRainAboveTheWaterEqualsAnUninterruptedOne) {
  expect_exact_resume("wcsph", 240, /*above_water=*/true);
}

// dfsph's warm start (the kept pressures) travels in the file: without it the resumed solves
// would start cold and end elsewhere.
TEST(Checkpoint, ResumedIncompressibleRunEqualsAnUninterruptedOne) {
  expect_exact_resume("dfsph", 60);
}

// Expects read_checkpoint to refuse `file` with a one-line input error containing `fragment`.
void expect_refused(const std::string& file, const std::string& fragment) {
  try {
    read_checkpoint(file);
    FAIL() << file << " was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kUsage);
    const std::string msg = e.what();
    EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
    EXPECT_NE(msg.find(file), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

TEST(Checkpoint, CorruptTruncatedAndForeignFilesAreRefused) {
  test::ScratchDir dir;
  auto sim = fresh();
  for (int k = 0; k < 60; ++k) sim->step();
  const CheckpointData good = sim->checkpoint();
  write_checkpoint(dir.path("good.h5"), good);
  const std::string bytes = test::read_text(dir.path("good.h5"));
  test::write_text(dir.path("truncated.h5"), bytes.substr(0, bytes.size() / 2));
  test::write_text(dir.path("text.h5"), "ncols 3\nnrows 3\n");
  {
    H5File foreign = H5File::create(dir.path("foreign.h5"));
    foreign.write("/data", std::vector<float>{1, 2, 3}, {3});
  }
  for (const auto& [name, version] : {std::pair{"version.h5", 99}, std::pair{"v2.h5", 2}}) {
    // a future schema version, and one from before the SPH integration changed
    H5File f = H5File::create(dir.path(name));
    f.attribute("/", "schema_version", static_cast<std::int64_t>(version));
    f.create_group("/terrain");
  }
  CheckpointData nan = good;
  nan.particles.f[kX][3] = std::nanf("");
  write_checkpoint(dir.path("nan.h5"), nan);
  write_checkpoint(dir.path("short.h5"), good);
  {  // replace /particles/ax by a dataset one value short
    const hid_t f = H5Fopen(dir.path("short.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    H5Ldelete(f, "/particles/ax", H5P_DEFAULT);
    const hsize_t n = good.particles.size() - 1;
    const hid_t space = H5Screate_simple(1, &n, nullptr);
    const hid_t set = H5Dcreate2(f, "/particles/ax", H5T_NATIVE_FLOAT, space, H5P_DEFAULT,
                                 H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(set, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, good.ax.data());
    H5Dclose(set);
    H5Sclose(space);
    H5Fclose(f);
  }

  EXPECT_NO_THROW(read_checkpoint(dir.path("good.h5")));
  expect_refused(dir.path("truncated.h5"), "HDF5");
  expect_refused(dir.path("text.h5"), "not an HDF5 file");
  expect_refused(dir.path("foreign.h5"), "not a runnel checkpoint");
  expect_refused(dir.path("version.h5"), "schema version 99");
  expect_refused(dir.path("v2.h5"), "schema version 2 was written before the SPH time integration");
  expect_refused(dir.path("nan.h5"), "/particles/x[3] is not a finite number");
  expect_refused(dir.path("short.h5"), "/particles/ax");
  expect_refused(dir.path("missing.h5"), "no such file");
}

TEST(Checkpoint, AFailedWriteLeavesThePreviousFileAndNoTemporary) {
  test::ScratchDir dir;
  auto sim = fresh();
  for (int k = 0; k < 30; ++k) sim->step();
  write_checkpoint(dir.path("c.h5"), sim->checkpoint());
  const std::string before = test::read_text(dir.path("c.h5"));
  // A writer that dies half way (as a full disk would).
  EXPECT_THROW(write_path_atomically(dir.path("c.h5"),
                                     [](const std::string& temporary) {
                                       test::write_text(temporary, "half a checkpoint");
                                       throw runtime_error("disk full");
                                     }),
               Error);
  EXPECT_EQ(test::read_text(dir.path("c.h5")), before);
  int files = 0;
  for (auto& e : std::filesystem::directory_iterator(dir.root())) {
    (void)e;
    ++files;
  }
  EXPECT_EQ(files, 1) << "the temporary file must be removed";
  EXPECT_NO_THROW(read_checkpoint(dir.path("c.h5")));
}

}  // namespace
}  // namespace runnel
