// SPDX-License-Identifier: MIT
#include <charconv>
#include <cmath>

#include "cli/commands.hpp"
#include "runnel/core/error.hpp"

namespace runnel::cli {

void add_output_flags(CLI::App& cmd, OutputFlags& flags) {
  cmd.add_option(
         "--checkpoint-every", flags.checkpoint_every,
         "write DIR/checkpoints/step_XXXXXXXX.h5 every N steps (final.h5 is always written)")
      ->check(CLI::NonNegativeNumber);
  cmd.add_option("--keep-checkpoints", flags.keep_checkpoints, "keep the newest K checkpoints")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd.add_option("--series-every", flags.series_every,
                 "append the heightmap to DIR/series.h5 every N steps")
      ->check(CLI::NonNegativeNumber);
}

void OutputFlags::apply(RunOptions& options) const {
  options.checkpoint_every = checkpoint_every;
  options.keep_checkpoints = keep_checkpoints;
  options.series_every = series_every;
}

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
