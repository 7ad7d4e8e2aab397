// SPDX-License-Identifier: MIT
// libFuzzer target: the HDF5 checkpoint reader, and rebuilding the model it holds (its
// invariants, its digest, its mass balance), as `runnel resume` does.
#include "fuzz_target.hpp"
#include "runnel/models/checkpoint.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = runnel::fuzz::input_file(data, size, "h5");
  return runnel::fuzz::run_reader([&] { runnel::read_checkpoint(path); });
}
