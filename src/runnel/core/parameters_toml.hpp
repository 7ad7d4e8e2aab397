// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <vector>

#include "runnel/core/parameters.hpp"

namespace runnel {

// Reads TOML text into `params`, over the keys of params.table(): a [group] table per key's first
// component, [[layers]] for the strata. Unknown keys and tables, wrong types and out-of-range
// values throw an input error naming `origin` and the key.
void read_parameters_toml(Parameters& params, const std::string& text, const std::string& origin);

// Applies `--set key=value` overrides in order.
void apply_overrides(Parameters& params, const std::vector<std::string>& assignments);
// Refuses an assignment whose key is outside `groups` (e.g. {"sph"}): `what` (a command) reads
// nothing else, so the value would be ignored.
void require_override_groups(const std::vector<std::string>& assignments,
                             const std::vector<std::string>& groups, const std::string& what);

// The parameter set as TOML text that read_parameters_toml reads back to the same values
// (checkpoints store it).
std::string parameters_toml(const Parameters& params);

}  // namespace runnel
