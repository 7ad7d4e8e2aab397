// SPDX-License-Identifier: MIT
// libFuzzer target: the sweep file reader (TOML, the axes, the base scenario it names), the member
// count it computes before expanding, and the SLURM script it writes with every name quoted.
#include <string>

#include "fuzz_target.hpp"
#include "runnel/sweep/sweep.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = runnel::fuzz::input_file(data, size, "toml");
  return runnel::fuzz::run_reader([&] {
    const runnel::SweepSpec spec = runnel::read_sweep(path);
    if (runnel::sweep_member_count(spec) > 64) return;  // expanding is bounded, not fuzzed
    const auto members = runnel::expand_sweep(spec);
    (void)runnel::slurm_script(spec, members, "/tmp/runnel fuzz 'out'", "/usr/bin/runnel",
                               "1-00:00:00");
  });
}
