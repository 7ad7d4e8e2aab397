// SPDX-License-Identifier: MIT
#pragma once
#include <cstdio>
#include <string>

namespace runnel {

// One OpenCL build option that defines a float constant, " -DNAME=((float)(value))": the double
// written with 17 digits and cast to float by the kernel compiler, exactly as the host rounds it.
inline std::string float_define(const char* name, double value) {
  char buf[128];
  std::snprintf(buf, sizeof buf, " -D%s=((float)(%.17g))", name, value);
  return buf;
}

}  // namespace runnel
