// SPDX-License-Identifier: MIT
// The pressure solvers behind one interface: sph.solver offers exactly the registered methods and
// refuses any other name with their list; every registered method steps a block of water, reports
// itself and its pressures, and the state it keeps between steps travels with its particles
// through the hash's sort.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>

#include "runnel/core/error.hpp"
#include "runnel/core/parameter_groups.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/sph/pressure/registry.hpp"
#include "runnel/sph/sph_solver.hpp"
#include "runnel/validation/tank.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

TEST(PressureRegistry, SphSolverOffersExactlyTheRegisteredMethods) {
  const std::vector<ParamSpec> specs = sph_parameters();
  const ParamSpec* solver = find_param(specs, "sph.solver");
  ASSERT_NE(solver, nullptr);
  const std::vector<std::string> names = pressure_method_names();
  ASSERT_GE(names.size(), 2u);
  EXPECT_EQ(solver->choices, names);
  EXPECT_EQ(solver->default_value, "\"" + names.front() + "\"");
  for (const std::string& name : names) {
    EXPECT_NE(solver->help.find(name + ", "), std::string::npos) << solver->help;
    EXPECT_EQ(pressure_method(name).name, name);
  }
}

TEST(PressureRegistry, AnUnregisteredSolverIsRefusedWithTheRegisteredNames) {
  try {
    pressure_method("isph");
    FAIL() << "an unregistered name was accepted";
  } catch (const Error& e) {
    for (const std::string& name : pressure_method_names())
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
  }
  test::ScratchDir dir;
  const auto r = test::run_cli({"run", "--generate", "plane", "--set", "sph.solver=isph", "--steps",
                                "1", "--out", dir.path("o")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("sph.solver"), std::string::npos) << r.err;
  for (const std::string& name : pressure_method_names())
    EXPECT_NE(r.err.find(name), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("o")));
}

// A jittered block of water 4 particles deep on a flat floor, at rest.
HostParticles resting_block() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> jitter(-0.005f, 0.005f);
  HostParticles p;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 6; ++k)
        p.push(0.7f + 0.1f * i + jitter(rng), 0.05f + 0.1f * j, 0.7f + 0.1f * k + jitter(rng), 0, 0,
               0, 1000.0f, 1e30f);
  return p;
}

class EveryPressureSolver : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryPressureSolver, StepsReportsItselfAndKeepsItsStateThroughTheSort) {
  Parameters params = default_parameters();
  params.set("sph.solver", GetParam());
  params.set("sph.walls", false);
  const SphSettings s = SphSettings::from(params, 0.1, 2.0);
  SphSolver solver(compute(), s, flat_floor(24, 24, 0.1), 2.0);
  solver.add(resting_block());
  for (int k = 0; k < 20; ++k) solver.step();
  EXPECT_NE(solver.solver_json().str().find("\"solver\": \"" + GetParam() + "\""),
            std::string::npos)
      << solver.solver_json().str();
  EXPECT_GE(solver.bytes_per_particle(), ParticleStore::bytes_per_particle());

  // Water 4 layers deep at rest on the floor: every pressure finite, the deepest ones positive and
  // at most that of a column twice as deep.
  const std::vector<float> p = solver.pressure();
  ASSERT_EQ(p.size(), solver.particles().size());
  const double column = 2.0 * 0.4 * s.rho0 * s.gravity;
  double highest = 0;
  for (float v : p) {
    ASSERT_TRUE(std::isfinite(v));
    highest = std::max(highest, double(v));
  }
  EXPECT_GT(highest, 0.0);
  EXPECT_LT(highest, column);

  // The particles put back in reverse order, each kept field tagged with the particle's id: the
  // hash's sort must carry every kept field with its particle.
  ParticleStore& store = solver.particles();
  HostParticles reversed = store.download();
  for (auto& field : reversed.f) std::reverse(field.begin(), field.end());
  std::reverse(reversed.sediment.begin(), reversed.sediment.end());
  std::reverse(reversed.contacts.begin(), reversed.contacts.end());
  std::reverse(reversed.id.begin(), reversed.id.end());
  store.upload(reversed);
  const std::vector<ParticleField> kept = solver.pressure_solver().kept_fields();
  for (ParticleField field : kept) {
    std::vector<float> tagged(reversed.size());
    for (std::size_t i = 0; i < tagged.size(); ++i)
      tagged[i] = 0.25f * static_cast<float>(reversed.id[i]) + static_cast<float>(field);
    store.upload_field(field, tagged);
  }
  solver.hash().build(store);
  const HostParticles sorted = store.download();
  ASSERT_EQ(sorted.size(), reversed.size());
  EXPECT_NE(sorted.id, reversed.id);  // the sort moved them
  for (ParticleField field : kept) {
    const std::vector<float> values = store.read_field(field);
    for (std::size_t i = 0; i < sorted.size(); ++i)
      ASSERT_EQ(values[i], 0.25f * static_cast<float>(sorted.id[i]) + static_cast<float>(field))
          << particle_field_info(field).name << " of particle " << sorted.id[i];
  }
}

INSTANTIATE_TEST_SUITE_P(Registered, EveryPressureSolver,
                         ::testing::ValuesIn(pressure_method_names()),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace runnel
