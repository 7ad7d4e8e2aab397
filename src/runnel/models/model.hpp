// SPDX-License-Identifier: MIT
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "runnel/core/heightmap.hpp"
#include "runnel/core/parameters.hpp"
#include "runnel/io/json.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/models/fields.hpp"
#include "runnel/models/interaction.hpp"
#include "runnel/models/mass_balance.hpp"

namespace runnel {

class Ground;

// How a model counts time: simulated seconds (sph, pipe), years (stream-power, geological time) or
// iterations (olsen, thermal, and the droplet model's batches), which have no physical duration.
enum class ModelClock { kSeconds, kIterations, kYears };
// "s", "yr" or "iterations" (metrics.json's "clock").
const char* clock_name(ModelClock clock);
// The clock's units as UDUNITS writes them (NetCDF, BMI): "s", "yr" or "1" (iterations).
const char* time_units(ModelClock clock);
// What follows a time in a progress line: " s", " yr" or "".
const char* clock_suffix(ModelClock clock);

// What a model is, in the spirit of Landlab's component metadata: its registry key, the class
// named after its paper, the citation, its parameter group and the fields it reads and writes.
struct ModelInfo {
  std::string name;        // registry key and --model value: "pipe"
  std::string class_name;  // "Erosion_Mei2007"
  std::string citation;
  std::string parameter_group;  // its parameters are PARAMETER_GROUP.* in docs/parameters.md
  ModelClock clock = ModelClock::kIterations;
  bool has_rain = false;
  std::vector<FieldUse> fields;
  // The model's own end-of-run figures, in the order summary_values() gives them: metrics that
  // `runnel sweep` can collect (an empty field for a member of another model).
  std::vector<std::string> summary_names;
  // An upper bound of the device memory the model takes a terrain vertex, without a ground
  // (memory_check.hpp adds the ground's): checked before any buffer exists, since an OpenCL
  // implementation may abort on a failed allocation. A test holds each model to it.
  double device_bytes_per_vertex = 128;
};

// Where a model's water has gone so far (m³; an iteration model's rain is per iteration): the rain
// it has received, the water that has left over the terrain's edges, and the water on the terrain
// now. `edges` splits the outflow by edge (west, east, north, south: x = 0, x = max, the first row,
// the last row) for the models that count it so (`per_edge`). outflow.csv is made of these.
struct WaterBudget {
  double rain = 0, outflow = 0, stored = 0;
  bool per_edge = false;
  std::array<double, 4> edges{};
};
inline constexpr const char* kEdgeNames[4] = {"west", "east", "north", "south"};

// One erosion model on one terrain. Every model advances the same way (`advance(dt)`, Landlab's
// run_one_step), reports the same mass balance and is checkpointed through the same HDF5 files.
class Model {
 public:
  virtual ~Model() = default;
  virtual const ModelInfo& info() const = 0;

  // One step of the model's own size (adaptive where the model has a stability limit); returns
  // the step taken, in the model's clock units.
  virtual double step() = 0;
  // Advances the clock by `dt` (s, yr or iterations): steps until the clock reaches time() + dt.
  // Iteration models take round(dt) whole steps; the models in seconds or years land on the
  // target, their last step shortened to it (limit_next_step). dt = 0 changes nothing.
  // `after_step`, if given, runs after each step (a validation watching the state as it goes).
  void advance(double dt, const std::function<void()>& after_step = {});
  // Whether the clock has reached `target` (to a relative 10⁻¹², so that a clock summed from many
  // steps still lands on it), and one step that does not pass it: the loop advance() runs, for
  // callers that do their own work between steps (runnel run).
  bool reached(double target) const;
  void step_towards(double target);

  virtual double time() const = 0;
  // The length of the next step, in clock units: the step an adaptive model's stability limit chose
  // after its latest step (SPH: 0 before its first), or its fixed one (BMI's get_time_step).
  virtual double step_size() const = 0;
  // A model in seconds or years shortens its next step to at most `most`, so advance() lands on
  // its target; an iteration model takes its own.
  virtual void limit_next_step(double most) { (void)most; }
  virtual std::uint64_t steps() const = 0;
  virtual const Parameters& parameters() const = 0;

  // The terrain as it is now (float view of the fixed-point state) and as it started.
  virtual Heightmap terrain() = 0;
  virtual const Heightmap& initial_terrain() const = 0;
  // The terrain's exact heights in metres (row 0 the northern row; each a count of the height
  // quantum times the quantum, exact in a double), and new heights from a coupler (Landlab's uplift
  // or hillslope diffusion between storms): rounded to the quantum and booked in the mass balance
  // as an imposed source (MassBalance::imposed), never as erosion or deposition. Refused with a
  // layer stack, whose strata cannot tell what the coupler's change was made of.
  virtual std::vector<double> elevation() = 0;
  virtual void set_elevation(const std::vector<double>& metres) = 0;
  // The scenario's rain as a rate over the whole terrain, m/s (0: the model takes no rain field),
  // and a rain rate at every vertex in its place (BMI's atmosphere_rainfall_water__volume_flux),
  // kept as the rain mask's weights against that rate: it needs a scenario with rain. Refused by
  // a model whose rain is not a rate (the iteration models, the droplets).
  virtual double rain_rate() { return 0.0; }
  virtual void set_rain_rates(const std::vector<float>& metres_per_second);
  // The surface the erosion map and the eroded and deposited volumes are measured from: the
  // initial terrain, raised by the uplift so far in a model with tectonic uplift (stream-power),
  // so that they show what the surface processes did, not the rock's rise.
  virtual Heightmap erosion_reference() { return initial_terrain(); }
  virtual MassBalance mass_balance() = 0;
  // Water the model has rained onto the terrain so far, m³ (0 for models without rain).
  virtual double rain_volume() = 0;
  // Water standing on the terrain at t = 0 ([[water.bodies]], water.depth), m³.
  virtual double initial_water_volume() const { return 0.0; }
  // The water's budget now (outflow.csv, the overland-flow validation); none for a model whose
  // water is not a flow on the terrain (stream-power, thermal, the droplets).
  virtual std::optional<WaterBudget> water_budget() { return std::nullopt; }

  // The whole state for an exact restart, and back; restore() expects a model built from the
  // checkpoint's parameters and initial terrain (make_model_from_checkpoint does both).
  virtual CheckpointData checkpoint() = 0;
  virtual void restore(const CheckpointData& data) = 0;

  // The model's own entries for metrics.json (counters, effective settings).
  virtual JsonObject diagnostics() = 0;
  // One line on what limits the trust in this run's result, printed after it (empty: nothing).
  virtual std::string caution() { return {}; }
  // The model's own end-of-run figures, named as info().summary_names lists them.
  virtual std::vector<std::pair<std::string, double>> summary_values() { return {}; }
  // A short fragment for the progress line ("12,000 particles").
  virtual std::string status() = 0;
  // The work of the latest step in `work_unit()`s (particles, cells or droplet moves), for the
  // throughput in metrics.json.
  virtual double step_work() = 0;
  virtual const char* work_unit() const = 0;  // "particle_steps", "cell_steps", "droplet_steps"
  // The most device memory the model will hold (bytes), printed before a run starts.
  virtual double device_bytes() const = 0;
  // The run's layer stack (docs/layers.md), or nullptr when the terrain is one material.
  virtual Ground* ground() { return nullptr; }

  // Painting rain and showing water (runnel-viewer, interaction.hpp), or nullptr for a model that
  // takes no part in it.
  virtual Interactive* interactive() { return nullptr; }
  // The same, for callers that need no check: a model without one answers that it takes no
  // painted rain, has no scenario rain or rain mask to switch, and shows no water.
  Interactive& interaction();
};

// A coupler's rain rates (m/s a vertex) as rain-mask weights against the model's own `rate` (m/s):
// refused when the model has no rain, the count is not `vertices` or a rate is negative or not
// finite.
std::vector<float> rain_weights_for(const std::vector<float>& metres_per_second, double rate,
                                    std::size_t vertices, const std::string& model);

}  // namespace runnel
