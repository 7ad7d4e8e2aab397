// SPDX-License-Identifier: MIT
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/models/model.hpp"

namespace runnel {

// Every erosion model, registered in one place (registry.cpp) under its short name.
struct ModelEntry {
  const ModelInfo& (*info)();
  std::unique_ptr<Model> (*make)(ComputeContext& compute, const Parameters& params,
                                 const Heightmap& terrain);
  // The model's own parameters (its settings tables), listed in the parameter table in the
  // registry's order: the one place a new model is registered (docs/extending.md).
  std::vector<ParamSpec> (*parameters)();
};

const std::vector<ModelEntry>& model_registry();
std::vector<std::string> model_names();
// The entry of `name`; throws an input error (exit 2) listing the names for an unknown one.
const ModelEntry& model_entry(const std::string& name);

// The model run.model names, on `terrain`, with `params`.
// What make_model checks before it builds anything (the device's and the host's memory, standing
// water the model can hold): for a caller that builds several models in turn and must refuse
// before the first runs (runnel compare).
void check_model_preconditions(const ComputeContext& compute, const Parameters& params,
                               const Heightmap& terrain);
std::unique_ptr<Model> make_model(ComputeContext& compute, const Parameters& params,
                                  const Heightmap& terrain);
// The model a checkpoint holds, in the state it was saved in. A state whose mass does not balance
// (terrain change ≠ suspended + outflow + lost, to the quantum) is refused as damaged, naming
// `origin` (the file).
std::unique_ptr<Model> make_model_from_checkpoint(ComputeContext& compute,
                                                  const CheckpointData& data,
                                                  const std::string& origin = "checkpoint");

}  // namespace runnel
