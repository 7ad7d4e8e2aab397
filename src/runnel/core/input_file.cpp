// SPDX-License-Identifier: MIT
#include "runnel/core/input_file.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include "runnel/core/error.hpp"

namespace runnel {

const char* file_kind(unsigned mode) {
  if (S_ISREG(mode)) return "a regular file";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

void require_regular_input(const std::string& path, std::string_view what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    const int err = errno;
    throw input_error(path + ": cannot read the " + std::string(what) + " (" +
                      (err == ENOENT ? std::string("no such file") : std::strerror(err)) + ")");
  }
  if (!S_ISREG(st.st_mode))
    throw input_error(path + ": the " + std::string(what) + " is " + file_kind(st.st_mode) +
                      ", not a regular file");
}

std::string read_text_input(const std::string& path, std::string_view what,
                            std::uintmax_t max_bytes) {
  require_regular_input(path, what);
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw input_error(path + ": cannot open the " + std::string(what) + " for reading");
  const std::streamoff size = in.tellg();
  if (size < 0 || static_cast<std::uintmax_t>(size) > max_bytes)
    throw input_error(path + ": the " + std::string(what) + " has " + std::to_string(size) +
                      " bytes, more than the " + std::to_string(max_bytes) +
                      " such a file may have");
  in.seekg(0);
  std::string text(static_cast<std::size_t>(size), '\0');
  if (!in.read(text.data(), size))
    throw input_error(path + ": cannot read the " + std::string(what));
  return text;
}

void check_toml_key_depth(std::string_view text, const std::string& origin) {
  // A small scanner of TOML's structure: strings and comments skipped, keys told from values by
  // '=', inline tables and arrays tracked on a stack, the dots of each key counted.
  enum class Open { kArray, kInlineTable };
  std::vector<Open> open;
  bool expect_key = true, in_header = false;
  int dots = 0, line = 1;
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n; ++i) {
    const char c = text[i];
    if (c == '#') {
      while (i + 1 < n && text[i + 1] != '\n') ++i;
      continue;
    }
    if (c == '"' || c == '\'') {
      const bool triple = i + 2 < n && text[i + 1] == c && text[i + 2] == c;
      const std::size_t quote = triple ? 3 : 1;
      i += quote;
      for (; i < n; ++i) {
        if (text[i] == '\n') ++line;
        if (c == '"' && text[i] == '\\') {
          ++i;
          continue;
        }
        if (text[i] == c && (!triple || (i + 2 < n && text[i + 1] == c && text[i + 2] == c))) {
          i += quote - 1;
          break;
        }
        if (!triple && text[i] == '\n') break;  // unterminated: the parser says so
      }
      continue;
    }
    if (c == '\n') {
      ++line;
      if (open.empty()) {
        expect_key = true;
        in_header = false;
        dots = 0;
      }
      continue;
    }
    if (expect_key) {
      if (c == '[' && open.empty()) {
        in_header = true;
      } else if (c == ']' && in_header) {
        in_header = false;
        dots = 0;
      } else if (c == '.') {
        if (++dots >= kMaxTomlKeySegments)
          throw input_error(origin + ":" + std::to_string(line) + ": a key nested deeper than " +
                            std::to_string(kMaxTomlKeySegments) + " levels");
      } else if (c == '=') {
        expect_key = false;
        dots = 0;
      } else if (c == '}' && !open.empty() && open.back() == Open::kInlineTable) {
        open.pop_back();  // an empty inline table, {}
        expect_key = false;
      }
      continue;
    }
    if (c == '[') {
      open.push_back(Open::kArray);
    } else if (c == '{') {
      open.push_back(Open::kInlineTable);
      expect_key = true;
      dots = 0;
    } else if ((c == ']' && !open.empty() && open.back() == Open::kArray) ||
               (c == '}' && !open.empty() && open.back() == Open::kInlineTable)) {
      open.pop_back();
    } else if (c == ',' && !open.empty() && open.back() == Open::kInlineTable) {
      expect_key = true;
      dots = 0;
    }
  }
}

}  // namespace runnel
