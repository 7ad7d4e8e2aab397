// SPDX-License-Identifier: MIT
// Every model on a layered ground (docs/layers.md), over the model registry with no exemptions: a
// ground of erodibility 1 changes nothing bit for bit; a soft layer over hard rock is cut through
// and the cut slows at the hard rock; the volumes per layer add up to the terrain's change exactly;
// a frozen half loses no rock; a rain mask of 0 lets no rain fall; a layered run resumes exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "runnel/ground/ground.hpp"
#include "runnel/ground/strata.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/terrain_io.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

Heightmap steep_terrain() {
  return generate_terrain("fbm", 33, 33, 1.0, 5, {{"relief", 0.6}, {"octaves", 4}});
}

Parameters base_parameters(const std::string& model) {
  Parameters p = default_parameters();
  p.set("run.model", model);
  p.set("rain.max_particles", std::int64_t{400});
  p.set("pipe.edges", std::string("closed"));
  p.set("pipe.rain", 0.05);
  p.set("droplet.batch", std::int64_t{64});
  p.set("rain.rate", 2000.0);
  p.set("erosion.morphological_factor", 1000.0);
  p.set("stream_power.uplift", 0.0);
  return p;
}

// A soft stratum `thickness` m thick over a bedrock of erodibility `hard`.
Parameters two_layers(const std::string& model, double thickness, double hard) {
  Parameters p = base_parameters(model);
  p.add_layer({{"name", std::string("soft")}, {"thickness", thickness}}, "test");
  p.set("ground.bedrock_erodibility", hard);
  return p;
}

int busy_steps(const std::string& model) {
  return model == "sph" ? 120 : 30;
}

std::unique_ptr<Model> run(const Parameters& p, int steps) {
  auto model = make_model(compute(), p, steep_terrain());
  for (int k = 0; k < steps; ++k) model->step();
  return model;
}

const StoredField& field(const CheckpointData& d, const std::string& name) {
  for (const StoredField& f : d.fields)
    if (f.name == name) return f;
  throw std::runtime_error("no field " + name);
}

// Per vertex: how far the rock surface fell (quanta): initial surface − (height − sediment).
std::vector<std::int64_t> rock_lowering(const CheckpointData& d) {
  const StoredField& s = field(d, kGroundSediment);
  const StoredField& c = field(d, kGroundContacts);
  std::vector<std::int64_t> out(d.height_fixed.size());
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k] = c.i64[k * c.components] - (d.height_fixed[k] - s.i64[k]);
  return out;
}

class LayeredModel : public ::testing::TestWithParam<std::string> {};

TEST_P(LayeredModel, AGroundOfErodibilityOneChangesNothing) {
  const auto plain = run(base_parameters(GetParam()), busy_steps(GetParam()));
  const auto layered = run(two_layers(GetParam(), 0.05, 1.0), busy_steps(GetParam()));
  ASSERT_NE(layered->ground(), nullptr);
  EXPECT_EQ(plain->checkpoint().height_fixed, layered->checkpoint().height_fixed);
}

TEST_P(LayeredModel, CutsThroughTheSoftLayerAndSlowsAtTheHardRock) {
  const std::string model = GetParam();
  const int steps = busy_steps(model);
  const double q = base_parameters(model).real("erosion.height_quantum");
  // The control: the same ground soft throughout (a contact that changes nothing). The soft layer's
  // thickness is where the control cut half of its eroded vertices deeper.
  const CheckpointData control = run(two_layers(model, 0.0, 1.0), steps)->checkpoint();
  std::vector<std::int64_t> depths;
  for (std::int64_t d : rock_lowering(control))
    if (d > 0) depths.push_back(d);
  ASSERT_GT(depths.size(), 20u) << "the control run erodes";
  std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
  const std::int64_t contact_depth = depths[depths.size() / 2];
  const double thickness = static_cast<double>(contact_depth) * q;

  auto soft_run = run(two_layers(model, thickness, 1.0), steps);
  auto hard_run = run(two_layers(model, thickness, 0.05), steps);
  const auto below_contact = [&](const CheckpointData& d) {
    std::int64_t sum = 0;
    for (std::int64_t lowered : rock_lowering(d))
      sum += std::max<std::int64_t>(0, lowered - contact_depth);
    return sum;
  };
  const std::int64_t soft_below = below_contact(soft_run->checkpoint());
  const std::int64_t hard_below = below_contact(hard_run->checkpoint());
  ASSERT_GT(soft_below, 0) << "the soft ground is cut below the contact depth";
  EXPECT_GT(hard_below, 0) << "the cut reaches the hard rock";
  EXPECT_LT(hard_below, soft_below / 2) << "and slows there (erodibility 0.05)";

  // The per-layer accounting of the hard run: both layers eroded, the identity exact, and the
  // volumes those of the rock surface's fall measured independently here.
  const std::string report = hard_run->ground()->report().str();
  EXPECT_EQ(test::json_number(report, "layer_balance_quanta"), 0.0);
  const Strata& strata = hard_run->ground()->strata();
  const CheckpointData d = hard_run->checkpoint();
  std::vector<std::int64_t> rock(d.height_fixed.size());
  const StoredField& s = field(d, kGroundSediment);
  for (std::size_t k = 0; k < rock.size(); ++k) rock[k] = d.height_fixed[k] - s.i64[k];
  const auto eroded = eroded_per_material(strata, rock);
  std::int64_t soft = 0, hard = 0;
  for (std::size_t k = 0; k < rock.size(); ++k) {
    const std::int64_t lowered = strata.contact(0, k) - rock[k];
    ASSERT_GE(lowered, 0) << "the rock surface never rises";
    soft += std::min(lowered, strata.contact(0, k) - strata.contact(1, k));
    hard += std::max<std::int64_t>(0, lowered - (strata.contact(0, k) - strata.contact(1, k)));
  }
  EXPECT_EQ(eroded[0], soft);
  EXPECT_EQ(eroded[1], hard);
  EXPECT_GT(eroded[1], 0);
  EXPECT_EQ(hard_run->mass_balance().residual_quanta, 0);
}

TEST_P(LayeredModel, AFrozenHalfLosesNoRock) {
  test::ScratchDir dir;
  const Heightmap t = steep_terrain();
  Heightmap frozen(t.nx, t.ny, t.cell, 0.0f);
  for (int j = 0; j < t.ny; ++j)
    for (int i = 0; i < t.nx / 2; ++i) frozen.at(i, j) = 1.0f;
  write_terrain(dir.path("frozen.npy"), frozen);
  Parameters p = base_parameters(GetParam());
  p.set("ground.frozen_mask", dir.path("frozen.npy"));
  const auto lowered = rock_lowering(run(p, busy_steps(GetParam()))->checkpoint());
  std::int64_t thawed = 0;
  for (int j = 0; j < t.ny; ++j) {
    for (int i = 0; i < t.nx; ++i) {
      const std::int64_t l = lowered[static_cast<std::size_t>(j) * t.nx + i];
      if (frozen.at(i, j) != 0.0f) {
        ASSERT_EQ(l, 0) << "frozen vertex " << i << "," << j << " lost rock";
      } else {
        thawed += l;
      }
    }
  }
  EXPECT_GT(thawed, 0) << "the thawed half erodes";
}

TEST_P(LayeredModel, ARainMaskOfZeroLetsNoRainFallAndHalfAMaskHalfTheRain) {
  const ModelInfo& info = model_entry(GetParam()).info();
  if (!info.has_rain) GTEST_SKIP() << info.name << " has no rain";
  test::ScratchDir dir;
  const Heightmap t = steep_terrain();
  Heightmap none(t.nx, t.ny, t.cell, 0.0f), west(t.nx, t.ny, t.cell, 0.0f);
  for (int j = 0; j < t.ny; ++j)
    for (int i = 0; i <= t.nx / 2; ++i) west.at(i, j) = 1.0f;
  write_terrain(dir.path("none.npy"), none);
  write_terrain(dir.path("west.npy"), west);
  Parameters p = base_parameters(GetParam());
  p.set("ground.rain_mask", dir.path("none.npy"));
  auto dry = run(p, busy_steps(GetParam()));
  EXPECT_EQ(dry->rain_volume(), 0.0);
  EXPECT_EQ(dry->mass_balance().eroded, 0.0) << "no water, no erosion";

  const auto full = run(base_parameters(GetParam()), busy_steps(GetParam()));
  p.set("ground.rain_mask", dir.path("west.npy"));
  auto half = run(p, busy_steps(GetParam()));
  // The west 17 of 33 columns: 16.5 of 32 cells' width by the cell weights (the column at the
  // edge of the mask weighs half), 17/33 of the vertices.
  const double ratio = half->rain_volume() / full->rain_volume();
  EXPECT_NEAR(ratio, 0.5, 0.1) << info.name;
  if (info.name == "sph") {
    const CheckpointData d = half->checkpoint();
    ASSERT_GT(d.particles.size(), 0u);
    for (std::size_t k = 0; k < d.particles.size(); ++k) {
      if (d.particles.f[kAge][k] < 1e-6f) {  // just fallen: where the rain put it
        EXPECT_LE(d.particles.f[kX][k], (t.nx / 2 + 1) * t.cell);
      }
    }
  }
}

TEST_P(LayeredModel, ALayeredRunResumesExactly) {
  test::ScratchDir dir;
  const Parameters p = two_layers(GetParam(), 0.02, 0.2);
  const int n = busy_steps(GetParam()) / 2;
  auto straight = run(p, 2 * n);
  auto first = run(p, n);
  write_checkpoint(dir.path("mid.h5"), first->checkpoint());
  first.reset();
  auto resumed = make_model_from_checkpoint(compute(), read_checkpoint(dir.path("mid.h5")));
  ASSERT_NE(resumed->ground(), nullptr);
  for (int k = 0; k < n; ++k) resumed->step();
  const CheckpointData a = straight->checkpoint(), b = resumed->checkpoint();
  EXPECT_EQ(a.height_fixed, b.height_fixed);
  EXPECT_EQ(field(a, kGroundSediment).i64, field(b, kGroundSediment).i64);
  EXPECT_EQ(straight->ground()->exposed(), resumed->ground()->exposed());
}

INSTANTIATE_TEST_SUITE_P(Registry, LayeredModel, ::testing::ValuesIn(model_names()),
                         [](const auto& info) { return test::param_name(info.param); });

}  // namespace
}  // namespace runnel
