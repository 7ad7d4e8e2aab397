// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

namespace runnel {

// Every file runnel reads is first checked to be a regular file: a FIFO would block the reader
// forever, a device such as /dev/zero would feed it until memory runs out, a directory has no
// content. Throws input_error naming `path`, what it is, and `what` the file was meant to be.
void require_regular_input(const std::string& path, std::string_view what);

// What a stat() mode says a path is, for messages: "a FIFO (named pipe)", "a directory", ...
const char* file_kind(unsigned mode);

// The whole of a small text file (a scenario, a sweep, a terrain graph, a session log): a regular
// file of at most `max_bytes`, refused in one line otherwise.
inline constexpr std::uintmax_t kMaxTextInputBytes = 16u << 20;
std::string read_text_input(const std::string& path, std::string_view what,
                            std::uintmax_t max_bytes = kMaxTextInputBytes);

// TOML text whose keys nest deeper than `kMaxTomlKeySegments` (a.b.c... or [a.b.c...]) is
// refused before the TOML library sees it: its parser recurses once per segment and overflows
// the stack on a few hundred thousand. runnel's deepest key has four segments.
inline constexpr int kMaxTomlKeySegments = 64;
void check_toml_key_depth(std::string_view text, const std::string& origin);

}  // namespace runnel
