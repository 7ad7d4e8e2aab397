// SPDX-License-Identifier: MIT
// Kernel arguments are bound by name: a name the kernel does not have, or one left unset, fails
// with a message naming the kernel and the argument, never computes with the wrong buffer.
#include <gtest/gtest.h>

#include <string>

#include "runnel/compute/kernel.hpp"
#include "test_support.hpp"

using namespace runnel;

namespace {

const char* kSource = R"CL(
// A comment with __kernel in it and (parentheses), which the parser must not take for a kernel.
inline float twice(float v) { return 2.0f * v; }
__kernel void scale(__global float* values, const uint n, const float factor) {
  const uint i = get_global_id(0);
  if (i < n) values[i] = twice(values[i]) * factor;
}
__kernel void offset(__global float* values,
                     const uint n,
                     const float by) {
  const uint i = get_global_id(0);
  if (i < n) values[i] += by;
}
__kernel __attribute__((reqd_work_group_size(4, 1, 1))) void tiled(__global float* values, const uint n) {
  if (get_global_id(0) < n) values[get_global_id(0)] = 0.0f;
}
)CL";

using test::compute;

}  // namespace

TEST(KernelArguments, NamesAreReadFromTheSignature) {
  EXPECT_EQ(kernel_argument_names(kSource, "scale"),
            (std::vector<std::string>{"values", "n", "factor"}));
  EXPECT_EQ(kernel_argument_names(kSource, "offset"),
            (std::vector<std::string>{"values", "n", "by"}));
  EXPECT_EQ(kernel_argument_names(kSource, "tiled"),  // an attribute before the name
            (std::vector<std::string>{"values", "n"}));
  EXPECT_TRUE(kernel_argument_names(kSource, "twice").empty());  // not a kernel
  EXPECT_TRUE(kernel_argument_names(kSource, "missing").empty());
}

TEST(KernelArguments, BoundByNameWhateverTheOrder) {
  cl::Program program = compute().build_source(kSource, "");
  Kernel k(compute(), program, "scale");
  std::vector<float> v = {1, 2, 3, 4};
  cl::Buffer b(compute().context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, v.size() * 4,
               v.data());
  // Set in an order unlike the signature's.
  k.set("factor", 1.5f).set("values", b).set("n", cl_uint{3}).launch(4);
  compute().queue().enqueueReadBuffer(b, CL_TRUE, 0, v.size() * 4, v.data());
  EXPECT_EQ(v, (std::vector<float>{3, 6, 9, 4}));
}

TEST(KernelArguments, AnUnknownNameFailsNamingKernelAndArgument) {
  cl::Program program = compute().build_source(kSource, "");
  Kernel k(compute(), program, "offset");
  try {
    k.set("factor", 1.0f);
    FAIL() << "setting an argument the kernel does not have did not throw";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("offset"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("factor"), std::string::npos) << e.what();
  }
}

TEST(KernelArguments, AnArgumentLeftUnsetFailsAtLaunch) {
  cl::Program program = compute().build_source(kSource, "");
  Kernel k(compute(), program, "offset");
  cl::Buffer b(compute().context(), CL_MEM_READ_WRITE, 16);
  k.set("values", b).set("n", cl_uint{4});
  try {
    k.launch(4);
    FAIL() << "a launch with 'by' unset did not throw";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("'by'"), std::string::npos) << e.what();
  }
}

// PoCL renames an argument that shadows a builtin (`step` becomes `_cl_step`): the compiler's
// names are checked against the source's when the kernel is created, so such a kernel fails at
// once, naming the argument, instead of binding by a name the device does not know.
TEST(KernelArguments, TheCompilersNamesAreCheckedWhereReported) {
  const char* source = R"CL(
__kernel void shadow(__global float* values, const float step) {
  values[get_global_id(0)] = step;
}
)CL";
  cl::Program program = compute().build_source(source, "");
  cl::Kernel raw(program, "shadow");
  std::string reported;
  try {
    reported = raw.getArgInfo<CL_KERNEL_ARG_NAME>(1);
  } catch (const cl::Error&) {
    GTEST_SKIP() << "this OpenCL platform does not report argument names (CL_KERNEL_ARG_NAME)";
  }
  if (reported == "step") {
    EXPECT_NO_THROW(Kernel(compute(), program, "shadow"));
  } else {
    try {
      Kernel k(compute(), program, "shadow");
      FAIL() << "compiler name '" << reported << "' differs from 'step' but nothing threw";
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find("step"), std::string::npos) << e.what();
    }
  }
}

TEST(KernelLaunch, WorkGroupsLargerThanTheDeviceAllowsAreRefusedByName) {
  cl::Program program = compute().build_source(kSource, "");
  Kernel k(compute(), program, "tiled");
  ASSERT_GE(k.max_group(), 4u);  // every OpenCL device runs groups of 4
  std::vector<float> v(8, 1.0f);
  cl::Buffer b(compute().context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, v.size() * 4,
               v.data());
  k.set("values", b).set("n", cl_uint{8});
  try {
    k.launch_groups(1, k.max_group() + 1);
    FAIL() << "a group past the device's limit was launched";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("kernel tiled: work-groups of"), std::string::npos)
        << e.what();
  }
  k.launch_groups(2, 4);  // what reqd_work_group_size asks for
  compute().queue().enqueueReadBuffer(b, CL_TRUE, 0, v.size() * 4, v.data());
  EXPECT_EQ(v, std::vector<float>(8, 0.0f));
}
