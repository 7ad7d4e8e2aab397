// SPDX-License-Identifier: MIT
#include "runnel/models/registry.hpp"

#include "runnel/core/error.hpp"
#include "runnel/core/parameter_groups.hpp"
#include "runnel/core/parameters_toml.hpp"
#include "runnel/ground/ground_settings.hpp"
#include "runnel/models/droplet_model.hpp"
#include "runnel/models/memory_check.hpp"
#include "runnel/models/olsen_model.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/models/pipe_model.hpp"
#include "runnel/models/sph_model.hpp"
#include "runnel/models/stream_power_model.hpp"
#include "runnel/models/thermal_model.hpp"
#include "runnel/terrain/standing_water.hpp"

namespace runnel {
namespace {

template <typename M>
ModelEntry entry(std::vector<ParamSpec> (*parameters)()) {
  return {&M::model_info,
          [](ComputeContext& compute, const Parameters& params, const Heightmap& terrain)
              -> std::unique_ptr<Model> { return std::make_unique<M>(compute, params, terrain); },
          parameters};
}

// SPH's groups: the fluid, its rain and its erosion law.
std::vector<ParamSpec> sph_model_parameters() {
  std::vector<ParamSpec> all = sph_parameters();
  for (auto group : {rain_parameters, erosion_parameters})
    for (ParamSpec& spec : group()) all.push_back(std::move(spec));
  return all;
}

}  // namespace

const std::vector<ModelEntry>& model_registry() {
  static const std::vector<ModelEntry> registry = {
      entry<SphModel>(sph_model_parameters),   entry<DropletModel>(droplet_parameters),
      entry<PipeModel>(pipe_parameters),       entry<OlsenModel>(olsen_parameters),
      entry<ThermalModel>(thermal_parameters), entry<StreamPowerModel>(stream_power_parameters)};
  return registry;
}

std::vector<std::string> model_names() {
  std::vector<std::string> names;
  for (const ModelEntry& e : model_registry()) names.push_back(e.info().name);
  return names;
}

const ModelEntry& model_entry(const std::string& name) {
  std::string known;
  for (const ModelEntry& e : model_registry()) {
    if (e.info().name == name) return e;
    known += (known.empty() ? "" : ", ") + e.info().name;
  }
  throw input_error("model '" + name + "' is unknown; the models are " + known);
}

namespace {

// Refused before the first buffer: PoCL aborts the process when an allocation fails.
void require_memory_for(const ComputeContext& compute, const Parameters& params,
                        const Heightmap& terrain) {
  const std::string model = params.text("run.model");
  require_memory(compute,
                 memory_need(static_cast<double>(terrain.size()),
                             model_entry(model).info().device_bytes_per_vertex, has_ground(params),
                             static_cast<int>(params.layers().size())),
                 "the " + model + " model on " + std::to_string(terrain.nx) + " x " +
                     std::to_string(terrain.ny) + " vertices");
}

// Standing water needs a model that holds water on the terrain.
void require_water_for_standing_water(const Parameters& params) {
  if (!has_standing_water(params)) return;
  const std::string& name = params.text("run.model");
  if (name == "sph" || name == "pipe" || name == "olsen") return;
  throw input_error(
      std::string(params.entries("water.bodies").empty() ? "water.depth" : "water.bodies") +
      ": the " + name + " model holds no standing water (sph, pipe and olsen do); leave it out");
}

}  // namespace

void check_model_preconditions(const ComputeContext& compute, const Parameters& params,
                               const Heightmap& terrain) {
  require_memory_for(compute, params, terrain);
  require_water_for_standing_water(params);
}

std::unique_ptr<Model> make_model(ComputeContext& compute, const Parameters& params,
                                  const Heightmap& terrain) {
  const ModelEntry& entry = model_entry(params.text("run.model"));
  check_model_preconditions(compute, params, terrain);
  return entry.make(compute, params, terrain);
}

std::unique_ptr<Model> make_model_from_checkpoint(ComputeContext& compute, const CheckpointData& d,
                                                  const std::string& origin) {
  Parameters params = default_parameters();
  read_parameters_toml(params, d.parameters_toml, "checkpoint parameters");
  params.set("run.model", d.model);
  require_memory_for(compute, params, d.terrain);
  std::unique_ptr<Model> model = model_entry(d.model).make(compute, params, d.initial_terrain());
  model->restore(d);
  const MassBalance m = model->mass_balance();
  if (m.residual_quanta != 0) {
    throw input_error(origin + ": the stored state does not balance (" +
                      std::to_string(m.residual_quanta) +
                      " quanta unaccounted for): the file is damaged");
  }
  return model;
}

}  // namespace runnel
