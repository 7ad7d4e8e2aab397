// SPDX-License-Identifier: MIT
// What the two halves of runnel._runnel share: the compute contexts, parameter values from Python
// and arrays that own their memory.
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/core/parameters.hpp"

namespace runnel::python {

namespace py = pybind11;

// One OpenCL context per device, shared by every model on it (building the kernels is the slow
// part).
std::shared_ptr<ComputeContext> context_for(const std::string& device);

// Python values as parameter text: what `--set key=value` and a TOML file give.
void set_parameters(Parameters& p, const py::dict& values, const std::string& origin);

// A NumPy array owning `values` (moved in), of `shape`.
template <typename T>
py::array owned_array(std::vector<T> values, std::vector<py::ssize_t> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule free(owned, [](void* v) { delete static_cast<std::vector<T>*>(v); });
  return py::array_t<T>(shape, owned->data(), free);
}

// The grid's shape with `components` values a vertex (1: a 2-D array).
inline std::vector<py::ssize_t> grid_shape(int ny, int nx, int components) {
  std::vector<py::ssize_t> shape = {ny, nx};
  if (components > 1) shape.push_back(components);
  return shape;
}

void bind_terrain(py::module_& m);
void bind_model(py::module_& m);

}  // namespace runnel::python
