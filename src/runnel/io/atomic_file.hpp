// SPDX-License-Identifier: MIT
#pragma once
#include <cstdio>
#include <functional>
#include <string>

namespace runnel {

// Writes a file safely: into a temporary file in the same directory, flushed and synced, then
// renamed over the target. A crash or a full disk leaves the previous file intact.
// `write` gets an open FILE*; it throws on failure, and then the temporary file is removed.
void write_file_atomically(const std::string& path, const std::function<void(std::FILE*)>& write);

// A whole text file, atomically.
void write_text_atomically(const std::string& path, const std::string& text);

// The same for writers that need a path (HDF5): `write` creates and fills the temporary file at the
// path it is given; then it is synced and renamed over `path`.
void write_path_atomically(const std::string& path,
                           const std::function<void(const std::string& temporary)>& write);

// Removes the hidden temporaries (".PREFIX….tmpXXXXXX") a killed writer left in `dir`; returns
// how many. Call it where this process alone writes files of that prefix.
int remove_stale_temporaries(const std::string& dir, const std::string& prefix);

}  // namespace runnel
