// SPDX-License-Identifier: MIT
#pragma once
#include <cstdio>
#include <string>
#include <string_view>

namespace runnel {

// One OpenCL build option that defines a float constant, " -DNAME=((float)(value))": the double
// written with 17 digits and cast to float by the kernel compiler, exactly as the host rounds it.
inline std::string float_define(const char* name, double value) {
  char buf[128];
  std::snprintf(buf, sizeof buf, " -D%s=((float)(%.17g))", name, value);
  return buf;
}

// A number for a message: %g, so 1e+300 and nan read as themselves.
inline std::string format_number(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", value);
  return buf;
}

// Text from a file or a flag, safe to echo in a one-line message: in single quotes, control bytes
// (escape sequences, newlines) and bytes ≥ 0x7f written as \xNN, and cut after 40 characters. A
// hostile file then cannot clear the terminal or split the message over lines.
inline std::string quoted(std::string_view text) {
  std::string out = "'";
  std::size_t shown = 0;
  for (unsigned char c : text) {
    if (++shown > 40) {
      out += "...";
      break;
    }
    if (c < 0x20 || c >= 0x7f || c == '\\' || c == '\'') {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "'";
}

// A whole message made safe for a terminal: control bytes (escape sequences, newlines, carriage
// returns) and UTF-8's C1 controls written as \xNN; other UTF-8 text (≥, m³) kept. Every line
// runnel prints to stderr goes through here, whatever text of a file or a flag it quotes.
inline std::string terminal_safe(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t k = 0; k < text.size(); ++k) {
    const auto c = static_cast<unsigned char>(text[k]);
    const bool c1 = c == 0xc2 && k + 1 < text.size() &&
                    static_cast<unsigned char>(text[k + 1]) >= 0x80 &&
                    static_cast<unsigned char>(text[k + 1]) <= 0x9f;
    if (c < 0x20 || c == 0x7f || c1) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

}  // namespace runnel
