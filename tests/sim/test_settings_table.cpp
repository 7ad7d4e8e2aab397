// SPDX-License-Identifier: MIT
// Each settings group fills its struct and its kernel defines from its own rows of the parameter
// table: a value set by key reaches the member and the define it names, and run.model offers
// exactly the registry's models.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "runnel/compute/build_options.hpp"
#include "runnel/core/parameter_groups.hpp"
#include "runnel/models/droplet_model.hpp"
#include "runnel/models/olsen_model.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/models/pipe_model.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/sph/erosion.hpp"
#include "runnel/sph/sph_settings.hpp"
#include "runnel/terrain/thermal.hpp"

namespace runnel {
namespace {

// A value inside the key's range that differs from its default.
double other_value(const ParamSpec& spec) {
  const double d = std::stod(spec.default_value);
  const double v = d != spec.max_value ? (d + spec.max_value) / 2 : (d + spec.min_value) / 2;
  return spec.type == ParamType::kInteger ? std::floor(v) : v;
}

TEST(SettingsTable, EveryGroupKeyIsInTheTableWithItsGroupPrefix) {
  const std::pair<const char*, std::vector<ParamSpec>> groups[] = {
      {"sph.", sph_parameters()},         {"rain.", rain_parameters()},
      {"erosion.", erosion_parameters()}, {"thermal.", thermal_parameters()},
      {"droplet.", droplet_parameters()}, {"olsen.", olsen_parameters()},
      {"pipe.", pipe_parameters()}};
  for (const auto& [prefix, specs] : groups) {
    ASSERT_FALSE(specs.empty()) << prefix;
    for (const ParamSpec& spec : specs) {
      EXPECT_EQ(spec.key.rfind(prefix, 0), 0u)
          << spec.key << " is declared in the " << prefix << " group";
      EXPECT_NE(find_param(spec.key), nullptr) << spec.key << " is missing from parameter_table()";
    }
  }
}

TEST(SettingsTable, ASetValueReachesTheMemberAndTheKernelDefine) {
  // Real keys whose kernel define is the raw value: set each to another value and find it in the
  // build options exactly as the kernel compiler will read it.
  const std::pair<const char*, const char*> sph_defines[] = {
      {"sph.alpha_visc", "SPH_ALPHA_VISC"},
      {"sph.delta", "SPH_DELTA"},
      {"sph.rho0", "SPH_RHO0"},
      {"sph.gravity", "SPH_GRAVITY"},
      {"sph.restitution", "SPH_RESTITUTION"}};
  for (const auto& [key, define] : sph_defines) {
    Parameters p = default_parameters();
    const double v = other_value(*find_param(key));
    p.set(key, v);
    const SphSettings s = SphSettings::from(p, 0.1, 2.0);
    EXPECT_NE(s.build_options().find(float_define(define, v)), std::string::npos) << key;
  }
  Parameters p = default_parameters();
  p.set("pipe.min_tilt", 0.125);
  p.set("pipe.edges", std::string("closed"));
  const PipeSettings pipe = PipeSettings::from(p);
  EXPECT_EQ(pipe.min_tilt, 0.125);
  EXPECT_TRUE(pipe.closed());
  EXPECT_NE(pipe.build_options().find(float_define("PIPE_MIN_TILT", 0.125)), std::string::npos);
  EXPECT_NE(pipe.build_options().find("-DPIPE_CLOSED=1"), std::string::npos);
  p.set("droplet.lifetime", std::int64_t{17});
  const DropletSettings droplet = DropletSettings::from(p);
  EXPECT_EQ(droplet.lifetime, 17);
  EXPECT_NE(droplet.build_options().find("-DDROPLET_LIFETIME=17"), std::string::npos);
  p.set("thermal.talus_angle", 33.0);
  EXPECT_EQ(ThermalSettings::from(p).talus_angle_deg, 33.0);
  p.set("olsen.capacity", 0.25);
  EXPECT_EQ(OlsenSettings::from(p).capacity, 0.25);
}

TEST(SettingsTable, ResolvedSphValuesFollowTheirParameters) {
  Parameters p =
      default_parameters();  // defaults: contact radius 0.5 dx, surface eps 0.01 dx, c0 automatic
  const SphSettings s = SphSettings::from(p, 0.2, 3.0);
  EXPECT_DOUBLE_EQ(s.spacing, 0.2);
  EXPECT_DOUBLE_EQ(s.h, std::stod(find_param("sph.h_factor")->default_value) * 0.2);
  EXPECT_DOUBLE_EQ(s.contact_radius,
                   std::stod(find_param("sph.contact_radius")->default_value) * 0.2);
  EXPECT_DOUBLE_EQ(s.surface_eps, std::stod(find_param("sph.surface_eps")->default_value) * 0.2);
  EXPECT_DOUBLE_EQ(s.c0, 30.0);
  EXPECT_DOUBLE_EQ(s.density_min, std::stod(find_param("sph.density_min")->default_value));
}

TEST(SettingsTable, RunModelOffersExactlyTheRegistrysModels) {
  for (const std::string& name : model_names()) {
    Parameters p = default_parameters();
    EXPECT_NO_THROW(p.set_text("run.model", "\"" + name + "\"")) << name;
  }
  Parameters p = default_parameters();
  EXPECT_THROW(p.set_text("run.model", "\"no-such-model\""), std::exception);
}

}  // namespace
}  // namespace runnel
