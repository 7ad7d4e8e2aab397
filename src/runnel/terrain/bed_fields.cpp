// SPDX-License-Identifier: MIT
#include "runnel/terrain/bed_fields.hpp"

namespace runnel {

cl::Buffer placeholder_buffer(ComputeContext& compute) {
  double one = 1.0;
  return cl::Buffer(compute.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, sizeof one, &one);
}

void bind_detachment(Kernel& kernel, const BedFields* bed, cl::Buffer& placeholder) {
  kernel.set("rock_erodibility", bed ? bed->rock_erodibility : placeholder)
      .set("sediment_erodibility", bed ? bed->sediment_erodibility : placeholder)
      .set("ground_sediment", bed ? bed->sediment : placeholder);
}

}  // namespace runnel
