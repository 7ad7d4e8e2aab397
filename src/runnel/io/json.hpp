// SPDX-License-Identifier: MIT
#pragma once
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

namespace runnel {

// A small JSON object writer for reports (metrics.json, bench and validate output). Keys keep
// their insertion order; numbers are written with enough digits to round-trip.
class JsonObject {
 public:
  JsonObject& add(const std::string& key, const std::string& value) {
    return raw(key, quote(value));
  }
  JsonObject& add(const std::string& key, const char* value) { return raw(key, quote(value)); }
  JsonObject& add(const std::string& key, double value) { return raw(key, number(value)); }
  JsonObject& add(const std::string& key, float value) { return raw(key, number(value)); }
  JsonObject& add(const std::string& key, int value) { return raw(key, std::to_string(value)); }
  JsonObject& add(const std::string& key, long value) { return raw(key, std::to_string(value)); }
  JsonObject& add(const std::string& key, long long value) {
    return raw(key, std::to_string(value));
  }
  JsonObject& add(const std::string& key, unsigned value) {
    return raw(key, std::to_string(value));
  }
  JsonObject& add(const std::string& key, unsigned long value) {
    return raw(key, std::to_string(value));
  }
  JsonObject& add(const std::string& key, unsigned long long value) {
    return raw(key, std::to_string(value));
  }
  JsonObject& add(const std::string& key, bool value) { return raw(key, value ? "true" : "false"); }
  JsonObject& add(const std::string& key, const JsonObject& value) { return raw(key, value.str()); }
  JsonObject& add(const std::string& key, const std::vector<JsonObject>& values) {
    std::string s = "[";
    for (std::size_t k = 0; k < values.size(); ++k) s += (k ? ", " : "") + values[k].str();
    return raw(key, s + "]");
  }
  // A pre-formatted JSON value.
  JsonObject& raw(const std::string& key, const std::string& json) {
    body_ += (body_.empty() ? "" : ", ") + quote(key) + ": " + json;
    return *this;
  }
  // Appends every entry of `other`.
  JsonObject& merge(const JsonObject& other) {
    if (!other.body_.empty()) body_ += (body_.empty() ? "" : ", ") + other.body_;
    return *this;
  }
  std::string str() const { return "{" + body_ + "}"; }

  static std::string quote(const std::string& s) {
    std::string out = "\"";
    for (unsigned char c : s) {
      switch (c) {
        case '"':
          out += "\\\"";
          break;
        case '\\':
          out += "\\\\";
          break;
        case '\n':
          out += "\\n";
          break;
        case '\t':
          out += "\\t";
          break;
        case '\r':
          out += "\\r";
          break;
        default:
          if (c < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            out += buf;
          } else {
            out += static_cast<char>(c);
          }
      }
    }
    return out + "\"";
  }
  static std::string number(double v) {
    if (!std::isfinite(v)) return "null";  // JSON has no NaN or infinity
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
  }

 private:
  std::string body_;
};

}  // namespace runnel
