// SPDX-License-Identifier: MIT
// The interactive session behind runnel-viewer, without a window: painted rain lands where it was
// painted and in the amount asked for, the scenario rain switches off, undo restores the terrain
// bytes, and a session log replays a session bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "runnel/core/error.hpp"
#include "runnel/interactive/session.hpp"
#include "runnel/models/grid_model.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/models/water_binning.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/terrain_io.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

Heightmap terrain() {
  return generate_terrain("fbm", 33, 33, 1.0, 5, {{"relief", 0.4}, {"octaves", 4}});
}

Parameters parameters(const std::string& model) {
  Parameters p = default_parameters();
  p.set("run.model", model);
  p.set("rain.max_particles", std::int64_t{600});
  p.set("droplet.batch", std::int64_t{64});
  p.set("erosion.morphological_factor", 1000.0);
  return p;
}

Session session(const std::string& model, bool global_rain = false) {
  return Session(compute(), parameters(model), terrain(), "", global_rain);
}

// A disc in the middle of the 32 m square.
RainDisc disc(double rate = 0.05) {
  return {16.0, 15.0, 5.0, rate};
}

class PaintsWater : public ::testing::TestWithParam<std::string> {};

TEST_P(PaintsWater, PaintedDepthLandsOnTheDiscsVerticesAndNowhereElse) {
  Session s = session(GetParam());
  auto& grid = dynamic_cast<GridModel&>(s.model());
  for (int k = 0; k < 3; ++k) s.step();  // the scenario rain is off: nothing falls
  EXPECT_EQ(s.model().rain_volume(), 0.0);
  for (float d : s.model().interaction().water_view().depth) ASSERT_EQ(d, 0.0f);

  s.set_rain({disc()});
  const double dt = s.step();  // the painted water comes after the step's flow
  const std::vector<int> inside = vertices_in_disc(33, 33, 1.0, disc());
  const std::set<int> expected(inside.begin(), inside.end());
  const std::vector<float> depth = s.model().interaction().water_view().depth;
  const float painted = static_cast<float>(disc().rate * dt);
  for (int k = 0; k < static_cast<int>(depth.size()); ++k) {
    if (expected.count(k)) {
      ASSERT_EQ(depth[k], painted) << "vertex " << k;
    } else {
      ASSERT_EQ(depth[k], 0.0f) << "vertex " << k << " is outside the disc";
    }
  }
  // π r² = 78.5 m²; the disc's 81 vertices stand for 81 m².
  EXPECT_EQ(inside.size(), 81u);
  EXPECT_DOUBLE_EQ(s.model().rain_volume(), static_cast<double>(painted) * inside.size());
  for (int k = 0; k < 20; ++k) s.step();
  EXPECT_EQ(grid.mass_balance().residual_quanta, 0);
}

// A sink drains the water standing in its disc every step, and the sediment that water held settles
// there: terrain + suspended sediment stay exact.
TEST_P(PaintsWater, ASinkDrainsItsDiscAndTheLoadSettles) {
  Session s = session(GetParam());
  s.set_rain({disc(0.2)});
  for (int k = 0; k < 15; ++k) s.step();
  const RainDisc sink{16.0, 15.0, 3.0, -1.0};
  s.set_rain({disc(0.2), sink});
  s.step();
  const std::vector<float> depth = s.model().interaction().water_view().depth;
  const std::vector<int> drained = vertices_in_disc(33, 33, 1.0, sink);
  ASSERT_FALSE(drained.empty());
  for (int k : drained) EXPECT_EQ(depth[k], 0.0f) << "vertex " << k;
  double wet = 0;
  for (float d : depth) wet += d;
  EXPECT_GT(wet, 0.0) << "the rest of the disc's water stays";
  EXPECT_EQ(s.model().mass_balance().residual_quanta, 0);
}

INSTANTIATE_TEST_SUITE_P(GridModels, PaintsWater, ::testing::Values("pipe", "olsen"));

TEST(Session, TheScenarioRainSwitchesOffAndOn) {
  Session s = session("pipe", true);
  s.step();
  const double one_step = s.model().rain_volume();
  EXPECT_GT(one_step, 0.0);
  s.set_global_rain(false);
  s.step();
  EXPECT_EQ(s.model().rain_volume(), one_step) << "no scenario rain while it is off";
  s.set_global_rain(true);
  s.step();
  EXPECT_GT(s.model().rain_volume(), one_step);
}

// Droplets that live one step with a brush of 3 cells change the terrain within 3 + 1 + 1 cells of
// where they fell: every change lies within the disc's radius plus that.
TEST(Session, DropletsFallOnThePaintedDisc) {
  Parameters p = parameters("droplet");
  p.set("droplet.lifetime", std::int64_t{1});
  Session s(compute(), p, terrain(), "", false);
  const std::vector<std::int64_t> before = s.model().checkpoint().height_fixed;
  for (int k = 0; k < 3; ++k) s.step();
  EXPECT_EQ(s.model().checkpoint().height_fixed, before) << "no droplets without rain";
  EXPECT_EQ(s.model().rain_volume(), 0.0);

  const RainDisc d{8.0, 20.0, 3.0, 2.0};  // 2 m/s on 28 m²: 56 droplets of 1 m³ a step
  s.set_rain({d});
  for (int k = 0; k < 5; ++k) s.step();
  EXPECT_NEAR(s.model().rain_volume(), 5 * d.rate * M_PI * d.radius * d.radius, 1.0);
  const std::vector<std::int64_t> after = s.model().checkpoint().height_fixed;
  int changed = 0;
  for (int k = 0; k < static_cast<int>(after.size()); ++k) {
    if (after[k] == before[k]) continue;
    ++changed;
    const double x = k % 33, z = k / 33;
    EXPECT_LE(std::hypot(x - d.x, z - d.z), d.radius + 5.0 + 1e-9) << "vertex " << k;
  }
  EXPECT_GT(changed, 0) << "the painted droplets eroded";
}

TEST(Session, SphRainsOnTheBrushDisc) {
  Session s = session("sph");
  for (int k = 0; k < 20; ++k) s.step();
  EXPECT_TRUE(s.model().interaction().water_view().points.empty()) << "no particles without rain";
  const RainDisc d{10.0, 20.0, 4.0, 0.5};
  s.set_rain({d});
  for (int k = 0; k < 40; ++k) s.step();
  const WaterView w = s.model().interaction().water_view();
  ASSERT_GT(w.points.size(), 0u);
  // Fresh drops fall almost straight down: within a particle spacing (0.5 m) of the disc.
  for (std::size_t i = 0; i < w.points.size(); i += 4) {
    EXPECT_LE(std::hypot(w.points[i] - d.x, w.points[i + 2] - d.z), d.radius + 0.5);
  }
  EXPECT_DOUBLE_EQ(s.model().rain_volume(), static_cast<double>(w.points.size() / 4) * 0.125);
}

// Over a sink the SPH particles evaporate at the next step, leaving their load where they are: a
// sink over the whole terrain empties it, and the mass balance stays exact.
TEST(Session, AnSphSinkEvaporatesTheParticlesOverIt) {
  Session s = session("sph");
  s.set_rain({{10.0, 20.0, 4.0, 0.5}});
  for (int k = 0; k < 60; ++k) s.step();
  const std::size_t before = s.model().interaction().water_view().points.size();
  ASSERT_GT(before, 0u);
  s.set_rain({{30.0, 2.0, 1.5, -1.0}});  // a sink in a corner, away from the water
  s.step();
  EXPECT_EQ(s.model().interaction().water_view().points.size(), before)
      << "nothing over it, nothing drained";
  s.set_rain({{16.0, 16.0, 100.0, -1.0}});  // one over everything
  for (int k = 0; k < 3; ++k) s.step();
  EXPECT_EQ(s.model().interaction().water_view().points.size(), 0u);
  EXPECT_EQ(s.model().mass_balance().residual_quanta, 0);
}

// The binned depth holds the particles' volume (the smoothing scatters, it does not lose), and a
// load and a velocity every particle shares are those of every wet vertex.
TEST(WaterBinning, KeepsTheVolumeTheLoadAndTheVelocity) {
  HostParticles p;
  std::uint64_t state = 12345;
  const auto uniform = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<float>((state >> 11) * 0x1.0p-53);
  };
  const int count = 500;
  for (int i = 0; i < count; ++i) p.push(40 * uniform(), 1.0f, 30 * uniform(), 1, 0, 0, 1000, 10);
  for (auto& s : p.sediment) s = 7;
  const double spacing = 0.5, quantum = 1e-4;
  const WaterView w = bin_particles(p, 21, 16, 2.0, spacing, quantum);
  double volume = 0;
  for (float d : w.depth) volume += d * 4.0;
  EXPECT_NEAR(volume, count * spacing * spacing * spacing, 1e-5 * volume);
  for (std::size_t k = 0; k < w.depth.size(); ++k) {
    if (w.depth[k] <= 1e-6f) continue;
    EXPECT_NEAR(w.load[k], 7 * quantum / 0.125, 1e-6);
    EXPECT_NEAR(w.speed[k], 1.0, 1e-5);
    EXPECT_NEAR(w.velocity[2 * k], 1.0, 1e-5);      // x
    EXPECT_NEAR(w.velocity[2 * k + 1], 0.0, 1e-6);  // z
  }
  EXPECT_EQ(w.points.size(), 4u * count);
}

class Undo : public ::testing::TestWithParam<std::string> {};

TEST_P(Undo, RestoresTheTerrainBytesOfTheStrokesStart) {
  Session s = session(GetParam(), true);
  for (int k = 0; k < 10; ++k) s.step();
  const CheckpointData start = s.model().checkpoint();
  const double rain_at_start = s.model().rain_volume();
  s.begin_stroke();
  s.set_rain({disc(0.5)});
  for (int k = 0; k < 30; ++k) s.step();
  s.end_stroke();
  s.set_rain({});
  for (int k = 0; k < 10; ++k) s.step();
  ASSERT_NE(s.model().checkpoint().height_fixed, start.height_fixed) << "the stroke changed it";
  ASSERT_TRUE(s.undo());
  const CheckpointData undone = s.model().checkpoint();
  EXPECT_EQ(undone.height_fixed, start.height_fixed);
  EXPECT_EQ(undone.steps, start.steps);
  EXPECT_EQ(undone.time, start.time);
  EXPECT_EQ(s.model().rain_volume(), rain_at_start);
  EXPECT_FALSE(s.undo()) << "one stroke, one undo";
}

INSTANTIATE_TEST_SUITE_P(Models, Undo, ::testing::Values("sph", "pipe", "olsen", "droplet"));

TEST(Session, UndoKeepsTheLastEightStrokes) {
  Session s = session("olsen");
  for (int k = 0; k < 10; ++k) {
    s.begin_stroke();
    s.step();
    s.end_stroke();
  }
  EXPECT_EQ(s.undo_depth(), Session::kUndoDepth);
  int undone = 0;
  while (s.undo()) ++undone;
  EXPECT_EQ(undone, 8);
  EXPECT_EQ(s.model().steps(), 2u) << "the ninth-last stroke began after two steps";
}

// A session with strokes, an undo, the rain switch, a model switch and a reset, replayed from its
// log (written and read back) in a session of its own.
void act(Session& s, const std::string& first_model) {
  const auto steps = [&](int n) {
    for (int k = 0; k < n; ++k) s.step();
  };
  steps(5);
  s.begin_stroke();
  s.set_rain({disc(0.3)});
  steps(7);
  s.set_rain({{12.0, 18.0, 4.0, 0.3}});  // the brush moved
  steps(6);
  s.end_stroke();
  s.set_rain({{20.0, 20.0, 3.0, 0.1}});  // a source keeps flowing
  steps(4);
  s.begin_stroke();
  s.set_rain({disc(0.4), {20.0, 20.0, 3.0, 0.1}});
  steps(5);
  s.end_stroke();
  ASSERT_TRUE(s.undo());
  s.set_global_rain(true);
  steps(6);
  s.switch_model(first_model == "pipe" ? "olsen" : "pipe");
  steps(5);
  s.begin_stroke();
  s.set_rain({disc(0.2)});
  steps(4);
  s.end_stroke();
  s.set_rain({});
  steps(3);
  s.end();
}

// On a layered ground, a frozen disc (mask 0) never erodes while the rain erodes around it; the
// stroke's undo brings back the scenario's mask (the checkpoint from before the painting has none),
// and a replay of the log reproduces the painted run bit for bit.
TEST(Session, AFrozenMaskStopsErosionUndoAndReplayIncluded) {
  Parameters p = parameters("pipe");
  p.add_layer({{"name", std::string("soft")}, {"thickness", 2.0}, {"erodibility", 2.0}}, "test");
  p.set("pipe.rain", 0.02);
  Session s(compute(), p, terrain(), "", true);
  const RainDisc frozen{16.0, 16.0, 6.0, 0.0};
  s.begin_stroke();
  ASSERT_TRUE(s.paint_mask(frozen, 0.0));
  s.end_stroke();
  const std::vector<std::int64_t> before = s.model().checkpoint().height_fixed;
  for (int k = 0; k < 60; ++k) s.step();
  const std::vector<std::int64_t> after = s.model().checkpoint().height_fixed;
  const std::vector<int> inside = vertices_in_disc(33, 33, 1.0, frozen);
  long long eroded_inside = 0, eroded_outside = 0;
  std::vector<bool> is_inside(after.size(), false);
  for (int k : inside) is_inside[k] = true;
  for (std::size_t k = 0; k < after.size(); ++k)
    (is_inside[k] ? eroded_inside : eroded_outside) +=
        std::max<std::int64_t>(0, before[k] - after[k]);
  EXPECT_EQ(eroded_inside, 0) << "frozen ground never loses rock";
  EXPECT_GT(eroded_outside, 0);
  EXPECT_EQ(s.model().mass_balance().residual_quanta, 0);

  ASSERT_TRUE(s.undo());
  ASSERT_NE(s.model().ground(), nullptr);
  for (float m : s.model().ground()->mask()) ASSERT_EQ(m, 1.0f) << "the scenario's mask is back";
  s.begin_stroke();
  ASSERT_TRUE(s.paint_mask({10.0, 20.0, 4.0, 0.0}, 0.25));
  s.end_stroke();
  for (int k = 0; k < 20; ++k) s.step();
  s.end();

  test::ScratchDir dir;  // through the file, as --replay reads it
  write_session_log(dir.path("strokes.json"), s.log());
  Session again(compute(), p, terrain(), "", true);
  again.start_replay(read_session_log(dir.path("strokes.json")));
  for (int guard = 0; !again.replay_finished() && guard < 1000; ++guard) again.step();
  EXPECT_EQ(again.model().checkpoint().height_fixed, s.model().checkpoint().height_fixed);
  EXPECT_EQ(again.model().ground()->mask(), s.model().ground()->mask());
  EXPECT_FALSE(session("pipe").paint_mask(frozen, 0.0)) << "no ground, no mask";
}

// A scenario with a rain mask (all 1): painting it dry stops the scenario's rain from the next
// step, a checkpoint of the painted state resumes dry, and undo brings the rain back.
class RainMask : public ::testing::TestWithParam<std::string> {};

TEST_P(RainMask, PaintedDryTheRainStopsAResumeStaysDryAndUndoBringsItBack) {
  test::ScratchDir dir;
  const Heightmap t = terrain();
  write_terrain(dir.path("wet.npy"), Heightmap(t.nx, t.ny, t.cell, 1.0f));
  Parameters p = parameters(GetParam());
  p.set("ground.rain_mask", dir.path("wet.npy"));
  p.set("rain.rate", 400.0);
  Session s(compute(), p, t, "", true);
  for (int k = 0; k < 10; ++k) s.step();
  const double wet = s.model().rain_volume();
  ASSERT_GT(wet, 0.0);
  s.begin_stroke();
  ASSERT_TRUE(s.paint_mask({16.0, 16.0, 100.0, 0.0}, 0.0, "rain"));  // the whole terrain
  s.end_stroke();
  const double dry = s.model().rain_volume();
  EXPECT_EQ(dry, wet) << "painting rains nothing";
  for (int k = 0; k < 10; ++k) s.step();
  EXPECT_EQ(s.model().rain_volume(), dry) << "no rain falls on a dry mask";

  write_checkpoint(dir.path("dry.h5"), s.model().checkpoint());
  auto resumed = make_model_from_checkpoint(compute(), read_checkpoint(dir.path("dry.h5")));
  for (int k = 0; k < 5; ++k) {
    s.step();
    resumed->step();
  }
  EXPECT_EQ(resumed->rain_volume(), dry) << "the painted mask is in the checkpoint";
  EXPECT_EQ(resumed->checkpoint().height_fixed, s.model().checkpoint().height_fixed);

  ASSERT_TRUE(s.undo());
  EXPECT_EQ(s.model().rain_volume(), wet);
  for (int k = 0; k < 5; ++k) s.step();
  EXPECT_GT(s.model().rain_volume(), wet) << "the scenario's mask rains again";
  EXPECT_FALSE(session(GetParam()).paint_mask({16.0, 16.0, 5.0, 0.0}, 0.0, "rain"))
      << "no rain mask, nothing to paint";
}

INSTANTIATE_TEST_SUITE_P(Models, RainMask, ::testing::Values("sph", "pipe", "olsen", "droplet"));

class Replay : public ::testing::TestWithParam<std::string> {};

TEST_P(Replay, ReproducesTheSessionBitForBit) {
  test::ScratchDir dir;
  Session live = session(GetParam());
  act(live, GetParam());
  write_session_log(dir.path("strokes.json"), live.log());

  Session again = session(GetParam());
  again.start_replay(read_session_log(dir.path("strokes.json")));
  for (int guard = 0; !again.replay_finished() && guard < 10000; ++guard) again.step();
  ASSERT_TRUE(again.replay_finished());
  const CheckpointData a = live.model().checkpoint(), b = again.model().checkpoint();
  EXPECT_EQ(a.model, b.model);
  EXPECT_EQ(a.height_fixed, b.height_fixed);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.time, b.time);
  ASSERT_EQ(a.fields.size(), b.fields.size());
  for (std::size_t k = 0; k < a.fields.size(); ++k) {
    EXPECT_EQ(a.fields[k].f32, b.fields[k].f32) << a.fields[k].name;
    EXPECT_EQ(a.fields[k].i64, b.fields[k].i64) << a.fields[k].name;
  }
  EXPECT_EQ(a.model_counters, b.model_counters);
}

INSTANTIATE_TEST_SUITE_P(Models, Replay, ::testing::Values("sph", "pipe", "droplet"));

TEST(SessionLog, BadFilesAreRefusedNamingTheProblem) {
  test::ScratchDir dir;
  const auto refused = [&](const std::string& text, const std::string& expected) {
    test::write_text(dir.path("log.json"), text);
    try {
      read_session_log(dir.path("log.json"));
      ADD_FAILURE() << "accepted: " << text;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ExitCode::kUsage);
      EXPECT_NE(std::string(e.what()).find("log.json"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  refused("{not json", "not JSON");
  refused(R"({"runnel_session_log": 7})", "not a runnel session log");
  refused(R"({"runnel_session_log": 1, "input": "", "model": "sph", "global_rain": true,
             "events": [{"event": "paint", "step": 3}]})",
          "unknown kind");
  refused(R"({"runnel_session_log": 1, "input": "", "model": "sph", "global_rain": true,
             "events": [{"event": "rain", "step": 3, "discs": [{"x_m": 1, "z_m": 1,
             "radius_m": -2, "rate_m_per_s": 1}]}]})",
          "radius_m > 0");
  refused(R"({"runnel_session_log": 1, "input": "", "model": "sph", "global_rain": true,
             "events": [{"event": "rain", "step": 3, "discs": [{"x_m": 1, "z_m": 1,
             "radius_m": 2, "rate_m_per_s": "fast"}]}]})",
          "missing or mistyped");
  refused(R"({"runnel_session_log": 1, "input": "", "model": "sph", "global_rain": true,
             "events": [{"event": "mask", "step": 3, "mask": "snow", "value": 0.5, "discs": [
             {"x_m": 1, "z_m": 1, "radius_m": 2, "rate_m_per_s": 0}]}]})",
          "the mask erodibility or rain");
  refused(R"({"runnel_session_log": 1, "model": "sph"})", "missing or mistyped");
}

}  // namespace
}  // namespace runnel
