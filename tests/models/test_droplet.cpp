// SPDX-License-Identifier: MIT
// The droplet model (Beyer 2015) in OpenCL: volume conserved exactly (outflow booked),
// deterministic, and it carves: the terrain changes and erosion follows the drainage.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "runnel/core/error.hpp"
#include "runnel/metrics/terrain_metrics.hpp"
#include "runnel/models/droplet_blocks.hpp"
#include "runnel/models/droplet_model.hpp"
#include "runnel/models/droplet_reference.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/terrain/generators.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

struct Outcome {
  std::vector<std::int64_t> before, after;
  long long outflow;
  Heightmap initial, final_terrain;
};

Outcome run_droplets(std::uint64_t seed, int batches) {
  const Heightmap t = generate_terrain("fbm", 129, 129, 1.0, 6, {{"relief", 0.25}});
  Parameters p = default_parameters();
  p.set("droplet.batch", std::int64_t{0});  // one droplet per 64 cells
  p.set("run.seed", static_cast<std::int64_t>(seed));
  DropletModel model(compute(), p, t);
  DeviceTerrain& terrain = model.state().terrain();
  Outcome o{terrain.download_fixed(), {}, 0, terrain.download(), {}};
  for (int k = 0; k < batches; ++k) model.step();
  o.after = terrain.download_fixed();
  o.outflow = model.outflow_quanta();
  o.final_terrain = terrain.download();
  return o;
}

TEST(DropletModel, ConservesVolumeExactly) {
  const Outcome o = run_droplets(3, 10);
  const long long before = std::accumulate(o.before.begin(), o.before.end(), 0LL);
  const long long after = std::accumulate(o.after.begin(), o.after.end(), 0LL);
  long long moved = 0;
  for (std::size_t k = 0; k < o.before.size(); ++k) moved += std::llabs(o.after[k] - o.before[k]);
  EXPECT_GT(moved, 0) << "the droplets erode";
  EXPECT_EQ(after + o.outflow, before) << "terrain change + outflow = 0, in quanta";
}

TEST(DropletModel, SameSeedSameTerrainAndOtherSeedOtherTerrain) {
  const Outcome a = run_droplets(5, 4), b = run_droplets(5, 4), c = run_droplets(6, 4);
  EXPECT_EQ(a.after, b.after);
  EXPECT_NE(a.after, c.after);
}

TEST(DropletModel, ErosionFollowsTheDrainage) {
  const Outcome o = run_droplets(7, 20);
  EXPECT_GT(metrics::erosion_flow_correlation(o.initial, o.final_terrain), 0.2);
}

// One batch of droplets on a rolling terrain against the plain C++ oracle (droplet_reference):
// the droplets' erosion brushes and bilinear deposits, step by step in lockstep.
TEST(DropletModel, ABatchMatchesThePlainCppReference) {
  const Heightmap hills = generate_terrain("fbm", 41, 37, 1.0, 6, {{"relief", 0.25}});
  Parameters p = default_parameters();
  p.set("droplet.lifetime", std::int64_t{8});
  p.set("droplet.batch", std::int64_t{24});
  DropletModel model(compute(), p, hills);
  DeviceTerrain& terrain = model.state().terrain();
  std::vector<std::int64_t> reference = terrain.download_fixed();
  const auto before = reference;
  const std::int64_t outflow = droplet_reference::batch(
      reference, hills.nx, hills.ny, terrain.quantum(), DropletSettings::from(p),
      static_cast<std::uint64_t>(p.integer("run.seed")), 0, 24);
  model.step();
  // The device reads float heights (rounded to 1e-7 of the height) and the droplets' changes are
  // thousands of quanta, so a floor() may fall differently and a brush weight with it: the two
  // agree to the vertex's change, not to the quantum.
  const auto device = terrain.download_fixed();
  double differ = 0, changed = 0, worst = 0;
  for (std::size_t k = 0; k < device.size(); ++k) {
    const double d = std::abs(device[k] - reference[k]);
    const double change = std::abs(reference[k] - before[k]);
    differ += d;
    changed += change;
    worst = std::max(worst, d / (3.0 + change));
  }
  EXPECT_GT(changed, 1e6) << "quanta: the droplets erode and deposit";
  EXPECT_LT(differ, 1e-4 * changed) << "in all";
  EXPECT_LT(worst, 0.05) << "of any vertex's change (+3 quanta)";
  EXPECT_NEAR(static_cast<double>(model.outflow_quanta()), static_cast<double>(outflow),
              3.0 + 1e-3 * outflow);
}

// droplet_apply's blocks decide only which work-item adds which droplet's changes: whole rows (a
// CPU), short runs (a GPU's many compute units) and square blocks give the same heights and
// outflow, bit for bit. Blocks too small to keep one launch's work-items apart are refused.
TEST(DropletModel, TheResultDoesNotDependOnHowTheBlocksAreCut) {
  const Heightmap hills = generate_terrain("fbm", 129, 97, 1.0, 6, {{"relief", 0.25}});
  Parameters p = default_parameters();
  p.set("run.seed", std::int64_t{11});
  const double radius = DropletSettings::from(p).radius;
  const auto cut_into = [&](int width) {
    DropletBlocks b = DropletBlocks::layout(hills.nx, hills.ny, radius, 1);
    b.width = width;
    b.blocks_x = (hills.nx + width - 1) / width;
    return b;
  };
  const DropletBlocks here = DropletBlocks::layout(hills.nx, hills.ny, radius, 2);
  const DropletBlocks cuts[] = {cut_into(hills.nx), cut_into(20), cut_into(here.rows), here};
  std::vector<std::vector<std::int64_t>> heights;
  std::vector<long long> outflows;
  for (const DropletBlocks& cut : cuts) {
    DropletModel model(compute(), p, hills, cut);
    for (int batch = 0; batch < 3; ++batch) model.step();
    heights.push_back(model.state().terrain().download_fixed());
    outflows.push_back(model.outflow_quanta());
  }
  EXPECT_NE(heights[0], DropletModel(compute(), p, hills).state().terrain().download_fixed())
      << "the droplets change the terrain";
  for (std::size_t c = 1; c < heights.size(); ++c) {
    EXPECT_EQ(heights[c], heights[0]) << "cut " << c;
    EXPECT_EQ(outflows[c], outflows[0]) << "cut " << c;
  }
  DropletBlocks thin = cuts[0];
  thin.rows -= 1;
  thin.blocks_y = (hills.ny + thin.rows - 1) / thin.rows;
  EXPECT_THROW(DropletModel(compute(), p, hills, thin), Error);
}

}  // namespace
}  // namespace runnel
