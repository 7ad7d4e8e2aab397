// SPDX-License-Identifier: MIT
// libFuzzer target: the NPY terrain reader (through read_terrain, as every command reads it).
#include "fuzz_target.hpp"
#include "runnel/terrain/terrain_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = runnel::fuzz::input_file(data, size, "npy");
  return runnel::fuzz::run_reader([&] { runnel::read_terrain(path); });
}
