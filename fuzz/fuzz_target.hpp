// SPDX-License-Identifier: MIT
// What every reader's fuzz target shares: the input written to a file of the reader's extension
// (the readers take paths), and the rule that decides a finding. A runnel::Error is the reader
// refusing the input, which is what it should do with garbage; anything else escaping (another
// exception, a crash, a sanitizer report) is a bug.
#pragma once
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "runnel/core/error.hpp"

namespace runnel::fuzz {

// A per-process file under /dev/shm (memory, not disk) holding the input. The pid is written to a
// fixed width: the path's length reaches the readers' messages, and with it which branches of the
// string code run, so a pid of another length steered the fixed-seed fuzzing elsewhere and made
// the suite's fuzz tests differ from run to run.
inline std::string input_file(const std::uint8_t* data, std::size_t size, const char* extension) {
  static const std::string path = [&] {
    char pid[16];
    std::snprintf(pid, sizeof pid, "%010d", static_cast<int>(getpid()));
    return "/dev/shm/runnel-fuzz-" + std::string(pid) + "." + extension;
  }();
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  return path;
}

template <typename Read>
int run_reader(Read read) {
  try {
    read();
  } catch (const runnel::Error&) {
    // Refused with a message: the reader did its job.
  }
  return 0;
}

}  // namespace runnel::fuzz
