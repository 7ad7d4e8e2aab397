// SPDX-License-Identifier: MIT
#include "runnel/models/model.hpp"

#include <cmath>

#include "runnel/core/error.hpp"

namespace runnel {

const char* clock_name(ModelClock clock) {
  return clock == ModelClock::kSeconds ? "s" : clock == ModelClock::kYears ? "yr" : "iterations";
}

const char* time_units(ModelClock clock) {
  return clock == ModelClock::kSeconds ? "s" : clock == ModelClock::kYears ? "yr" : "1";
}

const char* clock_suffix(ModelClock clock) {
  return clock == ModelClock::kSeconds ? " s" : clock == ModelClock::kYears ? " yr" : "";
}

void Model::advance(double dt, const std::function<void()>& after_step) {
  if (!(dt > 0)) return;
  auto one_step = [&] {
    step();
    if (after_step) after_step();
  };
  if (info().clock == ModelClock::kIterations) {
    for (long long k = std::llround(dt); k > 0; --k) one_step();
    return;
  }
  const double target = time() + dt;
  while (!reached(target)) {
    step_towards(target);
    if (after_step) after_step();
  }
}

bool Model::reached(double target) const {
  return time() >= target - 1e-12 * std::max(1.0, std::fabs(target));
}

// A model whose steps are adaptive shortens its last one to land on the target.
void Model::step_towards(double target) {
  limit_next_step(target - time());
  step();
}

void Model::set_rain_rates(const std::vector<float>&) {
  throw input_error("rain rates: the " + info().name + " model takes no rain field");
}

std::vector<float> rain_weights_for(const std::vector<float>& metres_per_second, double rate,
                                    std::size_t vertices, const std::string& model) {
  if (!(rate > 0))
    throw input_error("rain rates: the " + model + " model's scenario has no rain to scale " +
                      "(give it some, e.g. rain.intensity or pipe.rain)");
  if (metres_per_second.size() != vertices)
    throw input_error("rain rates: " + std::to_string(metres_per_second.size()) + " values for " +
                      std::to_string(vertices) + " vertices");
  std::vector<float> weights(vertices);
  for (std::size_t k = 0; k < vertices; ++k) {
    const float r = metres_per_second[k];
    if (!(std::isfinite(r) && r >= 0))
      throw input_error("rain rates: vertex " + std::to_string(k) + " is not a rate >= 0");
    weights[k] = static_cast<float>(r / rate);
  }
  return weights;
}

namespace {

class NoInteraction final : public Interactive {
 public:
  bool paints_rain() const override { return false; }
  void set_painted_rain(const std::vector<RainDisc>&) override {}
  bool set_global_rain(bool) override { return false; }
  WaterView water_view() override { return {}; }
  bool paint_rain_mask(const std::vector<int>&, float) override { return false; }
  bool has_rain_mask() const override { return false; }
};

}  // namespace

Interactive& Model::interaction() {
  static NoInteraction none;
  Interactive* own = interactive();
  return own != nullptr ? *own : none;
}

}  // namespace runnel
