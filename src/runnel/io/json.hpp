// SPDX-License-Identifier: MIT
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <type_traits>
#include <vector>

namespace runnel {

// A JSON object for reports (metrics.json, bench and validate output), held as nlohmann-json's
// ordered document: keys keep their insertion order, strings are escaped and numbers written to
// round-trip by the library. str() lays it out on one line with a space after each colon and comma
// (`{"key": value, ...}`), which keeps a report greppable and a command's output one line.
class JsonObject {
 public:
  using Document = nlohmann::ordered_json;

  template <typename T, typename = std::enable_if_t<std::is_arithmetic_v<T>>>
  JsonObject& add(const std::string& key, T value) {
    doc_[key] = value;  // a NaN or an infinity is written as null (JSON has none)
    return *this;
  }
  JsonObject& add(const std::string& key, const std::string& value) {
    doc_[key] = value;
    return *this;
  }
  JsonObject& add(const std::string& key, const char* value) {
    return add(key, std::string(value));
  }
  JsonObject& add(const std::string& key, const JsonObject& value) {
    doc_[key] = value.doc_;
    return *this;
  }
  JsonObject& add(const std::string& key, const std::vector<JsonObject>& values) {
    Document array = Document::array();
    for (const JsonObject& v : values) array.push_back(v.doc_);
    doc_[key] = std::move(array);
    return *this;
  }
  // Any other JSON value (an array of numbers, say).
  JsonObject& add(const std::string& key, Document value) {
    doc_[key] = std::move(value);
    return *this;
  }
  // Appends every entry of `other`.
  JsonObject& merge(const JsonObject& other) {
    for (const auto& [key, value] : other.doc_.items()) doc_[key] = value;
    return *this;
  }
  std::string str() const { return layout(doc_.is_null() ? Document::object() : doc_); }

 private:
  static std::string layout(const Document& v) {
    if (v.is_object()) {
      std::string s = "{";
      for (const auto& [key, value] : v.items())
        s += (s.size() > 1 ? ", " : "") + Document(key).dump() + ": " + layout(value);
      return s + "}";
    }
    if (v.is_array()) {
      std::string s = "[";
      for (const Document& item : v) s += (s.size() > 1 ? ", " : "") + layout(item);
      return s + "]";
    }
    return v.dump();
  }
  Document doc_;
};

}  // namespace runnel
