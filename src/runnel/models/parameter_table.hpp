// SPDX-License-Identifier: MIT
#pragma once
#include <string>

#include "runnel/core/parameters.hpp"

namespace runnel {

// runnel's parameter table: the drivers' keys, each model's groups in the registry's order, the
// ground's, the run's (docs/parameters.md).
const ParameterTable& parameter_table();

// Every key of runnel's table at its default.
Parameters default_parameters();

// A key of runnel's table; nullptr when it has none.
const ParamSpec* find_param(const std::string& key);

}  // namespace runnel
