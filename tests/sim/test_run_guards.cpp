// SPDX-License-Identifier: MIT
// The run loop's guard on conservation: a model whose volume stops balancing is stopped as a
// numerical failure (as a NaN is), with its last good state kept, instead of running on and
// reporting a broken balance as a result.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "runnel/core/error.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/models/grid_model.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/sim/run.hpp"
#include "runnel/validation/tank.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

// A grid model that claims, from its third step on, to have destroyed quanta it never took from
// the terrain: its balance stops closing there.
class LeakyModel final : public GridModel {
 public:
  LeakyModel(ComputeContext& compute, const Parameters& params, const Heightmap& terrain)
      : GridModel(compute, params, terrain) {}
  const ModelInfo& info() const override {
    static const ModelInfo leaky{"leaky",
                                 "Test_Leaky",
                                 "a test model",
                                 "thermal",
                                 ModelClock::kIterations,
                                 false,
                                 {{kTopographicElevation, FieldIntent::kInOut}},
                                 {},
                                 72};
    return leaky;
  }
  JsonObject diagnostics() override { return {}; }

 protected:
  double take_step() override { return 1.0; }
  long long lost_quanta() override { return steps() >= 3 ? 5 : 0; }
};

TEST(RunGuards, ABalanceThatStopsClosingStopsTheRunAndKeepsItsLastGoodState) {
  test::ScratchDir dir;
  Parameters params = default_parameters();
  params.set("run.model", std::string("thermal"));
  LeakyModel model(test::compute(), params, flat_floor(9, 9, 1.0));
  RunOptions o;
  o.out_dir = dir.path("o");
  o.quiet = true;
  o.until_step = 10;
  o.report_every = 1;
  try {
    run_model(test::compute(), model, o);
    FAIL() << "a run whose balance broke went on to its end";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kRuntime);
    EXPECT_NE(std::string(e.what()).find("mass balance no longer closes at step 3"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("failed.h5"), std::string::npos) << e.what();
  }
  EXPECT_EQ(model.steps(), 3u);
  EXPECT_FALSE(std::filesystem::exists(dir.path("o/final.h5")));
  EXPECT_EQ(read_checkpoint(dir.path("o/failed.h5")).steps, 0u);
}

}  // namespace
}  // namespace runnel
