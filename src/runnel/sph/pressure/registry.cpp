// SPDX-License-Identifier: MIT
#include "runnel/sph/pressure/registry.hpp"

#include "runnel/core/error.hpp"
#include "runnel/core/text.hpp"
#include "runnel/sph/pressure/dfsph/dfsph.hpp"
#include "runnel/sph/pressure/wcsph/wcsph.hpp"

namespace runnel {
namespace {

template <class Method>
std::unique_ptr<PressureSolver> make(ComputeContext& compute, cl::Program& program,
                                     const SphSettings& settings) {
  return std::make_unique<Method>(compute, program, settings);
}

}  // namespace

// The one place that knows the methods by name. sph.dt_max = 0 resolves to 0.01 s for wcsph (never
// binding at its acoustic steps) and 0.05 s for dfsph (whose flow CFL step would otherwise grow
// without bound where the water is slow).
const std::vector<PressureMethod>& pressure_methods() {
  static const std::vector<PressureMethod> methods = {
      {"wcsph", "weakly compressible (Tait equation, time step set by the sound speed c0)",
       /*incompressible=*/false, /*default_dt_max=*/0.01, &make<Wcsph>},
      {"dfsph",
       "incompressible (divergence-free SPH: two pressure solves a step, time step set by the "
       "flow, sph.cfl_flow)",
       /*incompressible=*/true, /*default_dt_max=*/0.05, &make<Dfsph>},
  };
  return methods;
}

std::vector<std::string> pressure_method_names() {
  std::vector<std::string> names;
  for (const PressureMethod& m : pressure_methods()) names.push_back(m.name);
  return names;
}

const PressureMethod& pressure_method(const std::string& name) {
  for (const PressureMethod& m : pressure_methods())
    if (m.name == name) return m;
  std::string registered;
  for (const std::string& n : pressure_method_names())
    registered += (registered.empty() ? "" : ", ") + n;
  throw input_error("sph.solver: unknown solver " + runnel::quoted(name) +
                    " (registered: " + registered + ")");
}

}  // namespace runnel
