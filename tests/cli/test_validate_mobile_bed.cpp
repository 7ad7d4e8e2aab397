// SPDX-License-Identifier: MIT
// `runnel validate mobile-bed --models pipe,sph`: both models on the flume, one JSON object with a
// run each, each run's outputs in its own folder; --models anywhere else is refused.
#include <gtest/gtest.h>

#include <filesystem>

#include "test_support.hpp"

namespace runnel {
namespace {

TEST(ValidateMobileBedCli, RunsThePipeModelAndSphEachInItsOwnFolder) {
  test::ScratchDir dir;
  const auto r = test::run_cli({"validate", "mobile-bed", "--resolution", "5", "--models",
                                "pipe,sph", "--out", dir.path("out")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::size_t pipe = r.out.find("\"model\": \"pipe\""),
                    sph = r.out.find("\"model\": \"sph\"");
  EXPECT_NE(pipe, std::string::npos) << r.out;
  EXPECT_NE(sph, std::string::npos) << r.out;
  for (const char* model : {"pipe", "sph"}) {
    const std::string run = dir.path(std::string("out/") + model);
    // The tables runnel.plot draws: each gauge measured and simulated, each profile's points.
    const std::string gauges = test::read_text(run + "/gauges.csv");
    EXPECT_EQ(gauges.substr(0, gauges.find('\n')), "gauge,x,y,source,t,surface");
    for (const char* gauge : {"\nG1,", "\nG2,", "\nG3,", "\nG4,"})
      EXPECT_NE(gauges.find(gauge), std::string::npos) << model << gauge;
    EXPECT_NE(gauges.find(",measured,"), std::string::npos) << model;
    EXPECT_NE(gauges.find(std::string(",") + model + ","), std::string::npos) << model;
    const std::string profiles = test::read_text(run + "/profiles.csv");
    EXPECT_EQ(profiles.substr(0, profiles.find('\n')), "profile,y,x,low,high,mean,model,simulated");
    EXPECT_TRUE(std::filesystem::exists(run + "/" + model + "/probes.csv")) << model;
    EXPECT_NE(test::read_text(run + "/" + model + "/metrics.json").find("\"mass_balance_abs\": 0"),
              std::string::npos)
        << model;
  }
  const auto refused = test::run_cli({"validate", "dambreak", "--models", "sph"});
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("--models"), std::string::npos) << refused.err;
}

}  // namespace
}  // namespace runnel
