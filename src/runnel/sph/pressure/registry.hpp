// SPDX-License-Identifier: MIT
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "runnel/compute/context.hpp"

namespace runnel {

class PressureSolver;
struct SphSettings;

// A registered pressure solver: what sph.solver names, and what the rest of runnel may know of it
// without asking for it by name.
struct PressureMethod {
  std::string name;     // the value of sph.solver
  std::string summary;  // one clause for `runnel params`
  // Water at rest is at ρ0 (a summation density the solves hold there), rather than compressed
  // by its own weight (a continuity density under an equation of state).
  bool incompressible = false;
  double default_dt_max = 0.01;  // s, what sph.dt_max = 0 resolves to
  std::unique_ptr<PressureSolver> (*make)(ComputeContext&, cl::Program&,
                                          const SphSettings&) = nullptr;
};

// Every registered method, the default first. Adding one: a folder beside this file with a class
// implementing PressureSolver, and one line in registry.cpp (docs/extending.md).
const std::vector<PressureMethod>& pressure_methods();
// The method called `name`; an unregistered name is an input_error listing the registered ones.
const PressureMethod& pressure_method(const std::string& name);
std::vector<std::string> pressure_method_names();

}  // namespace runnel
