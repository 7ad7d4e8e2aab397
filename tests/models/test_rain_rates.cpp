// SPDX-License-Identifier: MIT
// A coupler's rain field (Model::set_rain_rates, BMI's atmosphere_rainfall_water__volume_flux): the
// rain falls where and as fast as the field says, against an independent sum of the field.
#include <gtest/gtest.h>

#include "runnel/core/error.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/models/sph_model.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/terrain_io.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

Heightmap hills() {
  return generate_terrain("fbm", 33, 33, 1.0, 3, {{"relief", 0.3}, {"octaves", 3}});
}

// 3 mm/s on the western third of the vertices, 0.5 mm/s on the rest but one dry column.
std::vector<float> storm_field(const Heightmap& t) {
  std::vector<float> rates(t.h.size());
  for (int j = 0; j < t.ny; ++j)
    for (int i = 0; i < t.nx; ++i)
      rates[j * t.nx + i] = i < t.nx / 3 ? 3e-3f : (i == t.nx - 1 ? 0.0f : 5e-4f);
  return rates;
}

// A grid model's kernels read rain weights when its scenario has a rain mask: one of 1 everywhere.
Parameters pipe_with_rain_mask(const test::ScratchDir& dir) {
  Heightmap ones = hills();
  std::fill(ones.h.begin(), ones.h.end(), 1.0f);
  write_terrain(dir.path("mask.npy"), ones);
  Parameters p = default_parameters();
  p.set("run.model", std::string("pipe"));
  p.set("ground.rain_mask", dir.path("mask.npy"));
  return p;
}

TEST(RainRates, ThePipeModelRainsTheFieldItIsGiven) {
  test::ScratchDir dir;
  Parameters p = pipe_with_rain_mask(dir);
  p.set("pipe.rain", 0.01);
  auto model = make_model(compute(), p, hills());
  EXPECT_DOUBLE_EQ(model->rain_rate(), 0.01);
  const std::vector<float> rates = storm_field(model->initial_terrain());
  model->set_rain_rates(rates);
  model->advance(2.0);
  double expected = 0;  // Σ rate · cell² · t
  for (float r : rates) expected += r;
  expected *= 1.0 * 1.0 * 2.0;
  EXPECT_NEAR(model->rain_volume(), expected, 1e-6 * expected);  // the weights are float32
  EXPECT_EQ(model->mass_balance().residual_quanta, 0);
}

TEST(RainRates, SphRainsWhereTheFieldRainsAndAsMuch) {
  Parameters p = default_parameters();
  p.set("run.model", std::string("sph"));
  p.set("rain.intensity", 3600.0);  // 1 mm/s over the terrain
  p.set("rain.max_particles", std::int64_t{20000});
  auto model = make_model(compute(), p, hills());
  EXPECT_NEAR(model->rain_rate(), 1e-3, 1e-12);
  const Heightmap& t = model->initial_terrain();
  std::vector<float> rates(t.h.size(), 0.0f);  // rain on the western quarter only, 2 mm/s
  for (int j = 0; j < t.ny; ++j)
    for (int i = 0; i <= (t.nx - 1) / 4; ++i) rates[j * t.nx + i] = 2e-3f;
  model->set_rain_rates(rates);
  model->advance(4.0);
  const double west_area = (t.nx - 1) / 4.0 * (t.ny - 1) * t.cell * t.cell;
  const double expected = 2e-3 * west_area * 4.0;  // the cells wholly inside the wet quarter
  EXPECT_NEAR(model->rain_volume(), expected, 0.1 * expected);
  // Every drop fell in the west: none further east than the quarter's edge plus what the wind of
  // a few seconds' flow could carry it.
  const CheckpointData d = model->checkpoint();
  ASSERT_GT(d.particles.size(), 0u);
  int east = 0;
  for (std::size_t k = 0; k < d.particles.size(); ++k)
    if (d.particles.f[kX][k] > 0.75 * (t.nx - 1) * t.cell) ++east;
  EXPECT_EQ(east, 0);
}

TEST(RainRates, ARainFieldSurvivesACheckpoint) {
  test::ScratchDir dir;
  const Parameters p = pipe_with_rain_mask(dir);
  auto straight = make_model(compute(), p, hills()), first = make_model(compute(), p, hills());
  for (auto* m : {straight.get(), first.get()})
    m->set_rain_rates(storm_field(m->initial_terrain()));
  straight->advance(2.0);
  first->advance(1.0);
  write_checkpoint(dir.path("mid.h5"), first->checkpoint());
  auto resumed = make_model_from_checkpoint(compute(), read_checkpoint(dir.path("mid.h5")));
  resumed->advance(1.0);
  EXPECT_EQ(resumed->checkpoint().height_fixed, straight->checkpoint().height_fixed);
  EXPECT_EQ(resumed->rain_volume(), straight->rain_volume());
}

TEST(RainRates, AreRefusedWhereTheyCannotRain) {
  Parameters p = default_parameters();
  p.set("run.model", std::string("thermal"));
  auto thermal = make_model(compute(), p, hills());
  EXPECT_THROW(thermal->set_rain_rates(storm_field(thermal->initial_terrain())), Error);
  auto unmasked = make_model(
      compute(),
      [&] {
        Parameters q = p;
        q.set("run.model", std::string("pipe"));
        return q;
      }(),
      hills());
  EXPECT_THROW(unmasked->set_rain_rates(storm_field(unmasked->initial_terrain())), Error)
      << "its kernels were built without rain weights";
  test::ScratchDir dir;
  p = pipe_with_rain_mask(dir);
  auto pipe = make_model(compute(), p, hills());
  std::vector<float> bad = storm_field(pipe->initial_terrain());
  bad[5] = -1.0f;
  EXPECT_THROW(pipe->set_rain_rates(bad), Error);
  bad.pop_back();
  EXPECT_THROW(pipe->set_rain_rates(bad), Error);
  p.set("pipe.rain", 0.0);
  auto dry = make_model(compute(), p, hills());
  EXPECT_THROW(dry->set_rain_rates(storm_field(dry->initial_terrain())), Error);
}

}  // namespace
}  // namespace runnel
