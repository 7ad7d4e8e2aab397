// SPDX-License-Identifier: MIT
// One conformance suite over the model registry, no exemptions (style.md §4, after Landlab's
// test_components.py): metadata complete, declared outputs created, dt = 0 changes nothing, volume
// conserved exactly on a closed domain, deterministic, and a checkpoint round trip through an HDF5
// file continues exactly as the run that never stopped.
#include <gtest/gtest.h>

#include <memory>

#include "runnel/models/checkpoint.hpp"
#include "runnel/models/grid_model.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/terrain/generators.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;
using test::expect_same_state;

// A small, steep terrain every model acts on within a few dozen steps: slopes above the 40° talus
// angle for thermal, valleys for the water.
Heightmap small_terrain() {
  return generate_terrain("fbm", 33, 33, 1.0, 5, {{"relief", 0.6}, {"octaves", 4}});
}

// A case is a registered model, or the SPH model with its other solver ("sph_dfsph"): everything
// the suite asks of a model holds for both SPH solvers.
constexpr const char* kDfsphCase = "sph_dfsph";

std::vector<std::string> conformance_cases() {
  std::vector<std::string> cases = model_names();
  cases.emplace_back(kDfsphCase);
  return cases;
}

std::string model_of(const std::string& conformance_case) {
  return conformance_case == kDfsphCase ? "sph" : conformance_case;
}

Parameters small_parameters(const std::string& conformance_case) {
  Parameters p = default_parameters();
  p.set("run.model", model_of(conformance_case));
  if (conformance_case == kDfsphCase) p.set("sph.solver", std::string("dfsph"));
  p.set("rain.max_particles", std::int64_t{400});
  p.set("pipe.edges", std::string("closed"));  // a closed domain: nothing leaves
  p.set("pipe.rain", 0.05);
  p.set("droplet.batch", std::int64_t{64});
  p.set("rain.rate", 2000.0);                     // SPH: drops land within the first steps
  p.set("erosion.morphological_factor", 1000.0);  // and a few steps move material
  p.set("stream_power.uplift", 0.0);              // stream-power: incision alone
  return p;
}

std::unique_ptr<Model> make(const std::string& name) {
  return make_model(compute(), small_parameters(name), small_terrain());
}

// Steps that let every model move material: SPH needs its drops to land first.
int busy_steps(const Model& m) {
  return m.info().name == "sph" ? 120 : 30;
}

class ModelConformance : public ::testing::TestWithParam<std::string> {};

TEST_P(ModelConformance, MetadataIsComplete) {
  const ModelInfo& info = model_entry(model_of(GetParam())).info();
  EXPECT_EQ(info.name, model_of(GetParam()));
  EXPECT_EQ(info.class_name.rfind("Erosion_", 0), 0u) << "variants are named after their paper";
  EXPECT_FALSE(info.citation.empty());
  int parameters = 0;
  for (const ParamSpec& spec : parameter_table()) {
    if (spec.key.rfind(info.parameter_group + ".", 0) != 0) continue;
    ++parameters;
    EXPECT_FALSE(spec.help.empty()) << spec.key;
    if (spec.type == runnel::ParamType::kReal || spec.type == runnel::ParamType::kInteger) {
      EXPECT_FALSE(spec.unit.empty()) << spec.key << " has no unit";
    }
  }
  EXPECT_GT(parameters, 0) << "the parameter group " << info.parameter_group << " is empty";
  bool elevation = false;
  for (const FieldUse& use : info.fields) {
    EXPECT_NO_THROW(field_description(use.name)) << use.name << " is not in the dictionary";
    elevation |= use.name == kTopographicElevation && use.intent == FieldIntent::kInOut;
  }
  EXPECT_TRUE(elevation) << "every model erodes the terrain";
}

TEST_P(ModelConformance, DeclaredOutputsAreCreated) {
  auto model = make(GetParam());
  for (int k = 0; k < busy_steps(*model); ++k) model->step();
  const CheckpointData d = model->checkpoint();
  EXPECT_EQ(d.height_fixed.size(), small_terrain().size());
  for (const FieldUse& use : model->info().fields) {
    if (use.intent == FieldIntent::kIn || use.name == kTopographicElevation) continue;
    if (field_description(use.name).location == FieldLocation::kParticle) {
      EXPECT_GT(d.particles.size(), 0u) << use.name;
      continue;
    }
    bool found = false;
    for (const StoredField& f : d.fields) found |= f.name == use.name;
    EXPECT_TRUE(found) << use.name << " is declared but not created";
  }
  // And nothing undeclared: the state holds exactly the declared vertex fields.
  for (const StoredField& f : d.fields) {
    bool declared = false;
    for (const FieldUse& use : model->info().fields) declared |= use.name == f.name;
    EXPECT_TRUE(declared) << f.name << " is in the state but not declared";
  }
}

TEST_P(ModelConformance, ZeroDtChangesNothing) {
  auto model = make(GetParam());
  for (int k = 0; k < 10; ++k) model->step();
  const CheckpointData before = model->checkpoint();
  model->advance(0.0);
  expect_same_state(before, model->checkpoint());
}

TEST_P(ModelConformance, AdvanceMovesTheClockByDt) {
  auto model = make(GetParam());
  const bool seconds = model->info().clock != ModelClock::kIterations;  // seconds or years
  const double dt = seconds ? 0.05 : 7.0;
  model->advance(dt);
  EXPECT_GT(model->step_size(), 0.0);
  EXPECT_GE(model->time(), dt * (1 - 1e-9));
  if (!seconds) {
    EXPECT_EQ(model->steps(), 7u);
  }
}

TEST_P(ModelConformance, AdvanceLandsOnItsTargetWhereTheModelChoosesItsSteps) {
  // The models with a clock in seconds or years (pipe, SPH, stream-power): advance() shortens the
  // last step to land on the target, so a coupler's update_until ends where it asked; the step
  // after is the model's own again, and a checkpoint written there continues exactly.
  auto model = make(GetParam()), straight = make(GetParam());
  if (model->info().clock == ModelClock::kIterations)
    GTEST_SKIP() << model->info().name << " counts whole iterations";
  for (auto* m : {model.get(), straight.get()})
    for (int k = 0; k < 5; ++k) m->step();
  const double own_step = model->step_size();
  const double target = model->time() + 2.5 * own_step;
  for (auto* m : {model.get(), straight.get()}) m->advance(target - m->time());
  EXPECT_NEAR(model->time(), target, 1e-9 * target);
  EXPECT_LE(model->step_size(), own_step * 1.0000001 + 1.0) << "a step the limits chose";
  EXPECT_EQ(model->mass_balance().residual_quanta, 0);
  test::ScratchDir dir;
  write_checkpoint(dir.path("landed.h5"), model->checkpoint());
  model.reset();
  auto resumed = make_model_from_checkpoint(compute(), read_checkpoint(dir.path("landed.h5")));
  for (auto* m : {resumed.get(), straight.get()}) m->advance(1.5 * own_step);
  expect_same_state(straight->checkpoint(), resumed->checkpoint());
  EXPECT_EQ(resumed->mass_balance().residual_quanta, 0);
}

TEST_P(ModelConformance, ConservesVolumeExactlyOnAClosedDomain) {
  auto model = make(GetParam());
  for (int k = 0; k < busy_steps(*model); ++k) model->step();
  const MassBalance m = model->mass_balance();
  EXPECT_GT(m.eroded, 0.0) << "the model moves material";
  EXPECT_EQ(m.residual_quanta, 0) << "terrain change + suspended + outflow + lost, in quanta";
  EXPECT_LE(m.relative, 1e-6);
}

TEST_P(ModelConformance, IsDeterministic) {
  auto a = make(GetParam()), b = make(GetParam());
  for (int k = 0; k < busy_steps(*a); ++k) {
    a->step();
    b->step();
  }
  expect_same_state(a->checkpoint(), b->checkpoint());
}

TEST_P(ModelConformance, CheckpointRoundTripContinuesExactly) {
  test::ScratchDir dir;
  auto straight = make(GetParam()), first = make(GetParam());
  const int n = busy_steps(*straight) / 2;
  for (int k = 0; k < 2 * n; ++k) straight->step();
  for (int k = 0; k < n; ++k) first->step();
  write_checkpoint(dir.path("mid.h5"), first->checkpoint());
  first.reset();
  auto resumed = make_model_from_checkpoint(compute(), read_checkpoint(dir.path("mid.h5")));
  EXPECT_EQ(resumed->info().name, model_of(GetParam()));
  if (resumed->info().name == "sph") {  // the checkpoint records its solver
    EXPECT_EQ(resumed->parameters().text("sph.solver"),
              GetParam() == kDfsphCase ? "dfsph" : "wcsph");
  }
  for (int k = 0; k < n; ++k) resumed->step();
  expect_same_state(straight->checkpoint(), resumed->checkpoint());
}

// What a Landlab loop does between storms: read the heights, raise the interior (uplift), lower a
// band (a hillslope process), write them back.
std::vector<double> coupler_change(const Model& model, std::vector<double> z) {
  const Heightmap& t = model.initial_terrain();
  for (int j = 1; j < t.ny - 1; ++j)
    for (int i = 1; i < t.nx - 1; ++i) z[j * t.nx + i] += (j < t.ny / 2 ? 0.25 : -0.1);
  return z;
}

TEST_P(ModelConformance, ImposedHeightsAreAnExactExternalSource) {
  auto model = make(GetParam());
  const int n = busy_steps(*model) / 2;
  for (int k = 0; k < n; ++k) model->step();
  const std::vector<double> before = model->elevation();
  model->set_elevation(before);
  EXPECT_EQ(model->elevation(), before)
      << "heights read back are exact: writing them changes nothing";
  EXPECT_EQ(model->mass_balance().imposed, 0.0);

  const MassBalance surface = model->mass_balance();
  const std::vector<double> changed = coupler_change(*model, before);
  model->set_elevation(changed);
  const MassBalance after = model->mass_balance();
  double expected = 0;  // the same change, summed independently in quanta
  const double q = model->checkpoint().height_quantum, cell = model->initial_terrain().cell;
  for (std::size_t k = 0; k < changed.size(); ++k)
    expected += static_cast<double>(std::llround(changed[k] / q) - std::llround(before[k] / q));
  EXPECT_GT(expected, 0.0);
  EXPECT_DOUBLE_EQ(after.imposed, expected * q * cell * cell);
  EXPECT_EQ(after.residual_quanta, 0) << "the imposed change is a source, not an error";
  EXPECT_EQ(after.eroded, surface.eroded) << "nor erosion";
  EXPECT_EQ(after.deposited, surface.deposited) << "nor deposition";

  for (int k = 0; k < n; ++k) model->step();
  EXPECT_EQ(model->mass_balance().residual_quanta, 0);
  EXPECT_DOUBLE_EQ(model->mass_balance().imposed, after.imposed);
}

TEST_P(ModelConformance, ImposedHeightsSurviveACheckpoint) {
  test::ScratchDir dir;
  auto straight = make(GetParam()), first = make(GetParam());
  const int n = busy_steps(*straight) / 2;
  for (auto* m : {straight.get(), first.get()}) {
    for (int k = 0; k < n; ++k) m->step();
    m->set_elevation(coupler_change(*m, m->elevation()));
  }
  for (int k = 0; k < n; ++k) straight->step();
  write_checkpoint(dir.path("mid.h5"), first->checkpoint());
  first.reset();
  auto resumed = make_model_from_checkpoint(compute(), read_checkpoint(dir.path("mid.h5")));
  for (int k = 0; k < n; ++k) resumed->step();
  expect_same_state(straight->checkpoint(), resumed->checkpoint());
  EXPECT_EQ(resumed->mass_balance().imposed, straight->mass_balance().imposed);
  EXPECT_EQ(resumed->mass_balance().residual_quanta, 0);
}

INSTANTIATE_TEST_SUITE_P(Registry, ModelConformance, ::testing::ValuesIn(conformance_cases()),
                         [](const auto& info) { return test::param_name(info.param); });

}  // namespace
}  // namespace runnel
