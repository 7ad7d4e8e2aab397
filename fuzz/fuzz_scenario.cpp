// SPDX-License-Identifier: MIT
// libFuzzer target: the TOML scenario reader (parse, validate every key against the table).
#include <string>

#include "fuzz_target.hpp"
#include "runnel/sim/scenario.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  return runnel::fuzz::run_reader([&] { runnel::parse_scenario(text, "fuzz"); });
}
