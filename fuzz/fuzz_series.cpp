// SPDX-License-Identifier: MIT
// libFuzzer target: a run's series.h5 read for the NetCDF export, and the NetCDF writer on what the
// reader accepts, as `runnel export series.h5 --format netcdf` does.
#include <string>

#include "fuzz_target.hpp"
#include "runnel/sim/series_netcdf.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = runnel::fuzz::input_file(data, size, "h5");
  const std::string out = path + ".nc";
  return runnel::fuzz::run_reader([&] { runnel::write_series_netcdf(out, path); });
}
