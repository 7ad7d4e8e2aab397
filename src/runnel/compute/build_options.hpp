// SPDX-License-Identifier: MIT
#pragma once
#include "runnel/core/text.hpp"

namespace runnel {

// float_define, the one way a float constant reaches a kernel, lives in core/text.hpp so that the
// settings tables (core/) write their defines with it too.

}  // namespace runnel
