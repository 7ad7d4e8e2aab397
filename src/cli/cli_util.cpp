// SPDX-License-Identifier: MIT
#include <charconv>
#include <cmath>

#include "cli/commands.hpp"
#include "runnel/core/error.hpp"

namespace runnel::cli {

HeightRange parse_range(const std::string& text, const std::string& flag) {
  // The separator is the first ':' after the first character, so "-10:20" parses as [-10, 20].
  const auto colon = text.find(':', 1);
  HeightRange r;
  auto parse = [](const std::string& s, double& v) {
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    return ec == std::errc() && p == s.data() + s.size() && std::isfinite(v);
  };
  if (colon == std::string::npos || !parse(text.substr(0, colon), r.min) ||
      !parse(text.substr(colon + 1), r.max)) {
    throw input_error(flag + " " + text + ": expected MIN:MAX in metres");
  }
  if (!(r.max > r.min)) throw input_error(flag + " " + text + ": MAX must be greater than MIN");
  return r;
}

}  // namespace runnel::cli
