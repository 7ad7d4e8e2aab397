// SPDX-License-Identifier: MIT
#pragma once
#include <string>

namespace runnel {

// GDAL reports through a global handler; runnel reports through exceptions. Registers the drivers
// and silences the handler, once per process.
void init_gdal();
// GDAL's last error message, or a sentence saying it gave none.
std::string gdal_message();

}  // namespace runnel
