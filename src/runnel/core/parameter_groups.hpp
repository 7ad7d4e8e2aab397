// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

#include "runnel/core/parameters.hpp"

namespace runnel {

// Each settings group's parameters, from its own table (core/settings_table.hpp), in the group's
// file beside the struct they fill. parameter_table() lists them in this order between the
// terrain.* and run.* keys, which belong to the drivers.
std::vector<ParamSpec> sph_parameters();           // sph/sph_settings.cpp
std::vector<ParamSpec> rain_parameters();          // sph/rain_emitter.cpp
std::vector<ParamSpec> erosion_parameters();       // sph/erosion.cpp
std::vector<ParamSpec> thermal_parameters();       // terrain/thermal.cpp
std::vector<ParamSpec> droplet_parameters();       // models/droplet_model.cpp
std::vector<ParamSpec> olsen_parameters();         // models/olsen_model.cpp
std::vector<ParamSpec> pipe_parameters();          // models/pipe_model.cpp
std::vector<ParamSpec> stream_power_parameters();  // models/stream_power_model.cpp
std::vector<ParamSpec> ground_parameters();        // ground/ground_settings.cpp
std::vector<ParamSpec> sediment_parameters();      // ground/bedload.cpp
std::vector<ParamSpec> water_parameters();         // terrain/standing_water.cpp
std::vector<ParamSpec> probe_parameters();         // terrain/probes.cpp

}  // namespace runnel
