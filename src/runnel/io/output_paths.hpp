// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <vector>

namespace runnel {

// A file a command reads or writes, with what it is for a message ("--trace", "terrain file").
struct NamedPath {
  std::string what;
  std::string path;
};

// Refuses (input_error, before anything is written) every output that would destroy something:
// an output that is one of the inputs (by any name: links and "./a/../a" included), two outputs
// that are one file, and an output whose existing target is not a regular file (a device, a FIFO,
// a socket, a folder), which an atomic rename would replace.
void check_output_paths(const std::vector<NamedPath>& inputs,
                        const std::vector<NamedPath>& outputs);

// Each output file's folder exists (it is not created): checked before anything is written, so a
// command with several outputs never writes one and then refuses the next.
void require_output_folders(const std::vector<NamedPath>& outputs);

// The same refusal for one target, where it is about to be replaced (the writers' last guard).
void refuse_special_output(const std::string& path);

}  // namespace runnel
