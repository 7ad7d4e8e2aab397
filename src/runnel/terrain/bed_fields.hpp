// SPDX-License-Identifier: MIT
#pragma once
#include "runnel/compute/context.hpp"
#include "runnel/compute/kernel.hpp"

namespace runnel {

// The per-vertex fields through which a layer stack (ground/ground.hpp, docs/layers.md) reaches the
// kernels that erode: compiled with GROUND = 1 they read them, with GROUND = 0 never.
struct BedFields {
  cl::Buffer erodibility;           // the active layer's (float): sph, droplet
  cl::Buffer rock_erodibility;      // the rock's (float) ┐ BED_DETACHMENT in cl/common.cl:
  cl::Buffer sediment_erodibility;  // the sediment's     │ pipe, olsen, thermal
  cl::Buffer sediment;              // loose sediment (int64 quanta) ┘
  cl::Buffer talus;  // the exposed material's talus threshold (int64 quanta): thermal
};

// One value of room (8 bytes) for a kernel argument the kernel is compiled not to read.
cl::Buffer placeholder_buffer(ComputeContext& compute);
// The arguments of BED_DETACHMENT (rock_erodibility, sediment_erodibility, ground_sediment) from
// `bed`, or the placeholder for each when it is null.
void bind_detachment(Kernel& kernel, const BedFields* bed, cl::Buffer& placeholder);

}  // namespace runnel
