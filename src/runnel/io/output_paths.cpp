// SPDX-License-Identifier: MIT
#include "runnel/io/output_paths.hpp"

#include <sys/stat.h>

#include <filesystem>

#include "runnel/core/error.hpp"
#include "runnel/core/input_file.hpp"

namespace runnel {

namespace fs = std::filesystem;

namespace {

// The file a path names, made comparable: the canonical path of what exists (links followed),
// the parent's canonical path and the name for what does not exist yet.
fs::path identity(const std::string& path) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
  return ec ? fs::path(path).lexically_normal() : p;
}

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec) && !ec;
  return identity(a) == identity(b);
}

}  // namespace

void refuse_special_output(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return;  // nothing there yet
  if (S_ISREG(st.st_mode)) return;
  throw input_error(path + ": is " + file_kind(st.st_mode) + "; runnel writes only regular files");
}

void check_output_paths(const std::vector<NamedPath>& inputs,
                        const std::vector<NamedPath>& outputs) {
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    const NamedPath& out = outputs[k];
    if (out.path.empty()) continue;
    refuse_special_output(out.path);
    for (const NamedPath& in : inputs) {
      if (!in.path.empty() && same_file(in.path, out.path))
        throw input_error(out.what + " " + out.path + ": is the " + in.what +
                          " this command reads; write it to another file");
    }
    for (std::size_t j = 0; j < k; ++j) {
      if (!outputs[j].path.empty() && same_file(outputs[j].path, out.path))
        throw input_error(out.what + " " + out.path + ": is also the " + outputs[j].what +
                          "; give each output a file of its own");
    }
  }
}

void require_output_folders(const std::vector<NamedPath>& outputs) {
  namespace fs = std::filesystem;
  for (const NamedPath& out : outputs) {
    if (out.path.empty()) continue;
    const fs::path target(out.path);
    const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
      throw input_error(out.what + " " + out.path + ": the folder '" + dir.string() +
                        "' does not exist");
  }
}

}  // namespace runnel
