// SPDX-License-Identifier: MIT
#include "runnel/terrain/gdal_support.hpp"

#include <cpl_error.h>
#include <gdal.h>

#include <mutex>

namespace runnel {

void init_gdal() {
  static std::once_flag once;
  std::call_once(once, [] {
    GDALAllRegister();
    CPLSetErrorHandler(CPLQuietErrorHandler);
  });
}

std::string gdal_message() {
  const char* message = CPLGetLastErrorMsg();
  return message && *message ? message : "GDAL gave no reason";
}

}  // namespace runnel
