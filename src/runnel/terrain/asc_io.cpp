// SPDX-License-Identifier: MIT
// ESRI ASCII grid (.asc): a header of key/value lines, then nrows lines of ncols values, north
// first. The file's first row becomes grid row j = 0 (z points south, physics.md §1).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "runnel/core/error.hpp"
#include "runnel/io/atomic_file.hpp"
#include "runnel/terrain/terrain_io.hpp"

namespace runnel {
namespace {

// A cursor over the file's text that yields whitespace-separated tokens and knows its line.
class Tokenizer {
 public:
  explicit Tokenizer(const std::string& text) : text_(text) {}
  bool next(std::string_view& token) {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ >= text_.size()) return false;
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    token = std::string_view(text_).substr(start, pos_ - start);
    return true;
  }
  int line() const { return line_; }
  std::size_t pos() const { return pos_; }
  void rewind(std::size_t pos, int line) {
    pos_ = pos;
    line_ = line;
  }

 private:
  const std::string& text_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

bool parse_double(std::string_view token, double& value) {
  const char* first = token.data();
  if (!token.empty() && token[0] == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, token.data() + token.size(), value);
  return ec == std::errc() && ptr == token.data() + token.size();
}

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return out;
}

// Header: lines of "key value" where key starts with a letter; data starts at the first number.
// Every key known, once, with a finite value; the origin by its corner or its centre.
std::map<std::string, double> read_asc_header(Tokenizer& tokens, const std::string& path) {
  std::map<std::string, double> header;
  std::string_view key, value;
  for (;;) {
    const std::size_t pos = tokens.pos();
    const int line = tokens.line();
    if (!tokens.next(key)) break;
    if (!std::isalpha(static_cast<unsigned char>(key[0]))) {
      tokens.rewind(pos, line);
      break;
    }
    const std::string name = lower(key);
    static const char* known[] = {"ncols",     "nrows",     "xllcorner", "yllcorner",
                                  "xllcenter", "yllcenter", "cellsize",  "nodata_value"};
    if (std::find_if(std::begin(known), std::end(known),
                     [&](const char* k) { return name == k; }) == std::end(known)) {
      throw input_error(path + ": line " + std::to_string(line) +
                        ": unknown header key or non-numeric value " + quoted(key));
    }
    double number = 0.0;
    if (!tokens.next(value) || !parse_double(value, number) || !std::isfinite(number)) {
      throw input_error(path + ": line " + std::to_string(line) + ": header key " + quoted(key) +
                        " has no finite numeric value");
    }
    if (!header.emplace(name, number).second) {
      throw input_error(path + ": line " + std::to_string(line) + ": header key " + quoted(key) +
                        " appears twice");
    }
  }
  // The origin is given by its corner or by its centre, both coordinates the same way.
  if (header.count("xllcenter") + header.count("xllcorner") > 1 ||
      header.count("yllcenter") + header.count("yllcorner") > 1 ||
      header.count("xllcenter") != header.count("yllcenter")) {
    throw input_error(path + ": the header mixes xllcorner/yllcorner with xllcenter/yllcenter");
  }
  for (const char* required : {"ncols", "nrows", "cellsize"}) {
    if (!header.count(required))
      throw input_error(path + ": missing header key '" + required + "'");
  }
  return header;
}

}  // namespace

Heightmap read_asc(const std::string& path, NodataPolicy nodata) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw input_error(path + ": cannot open for reading");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  if (text.empty()) throw input_error(path + ": empty file, not an ESRI ASCII grid");

  Tokenizer tokens(text);
  std::map<std::string, double> header = read_asc_header(tokens, path);
  std::string_view value;
  const double ncols = header["ncols"], nrows = header["nrows"];
  if (ncols != std::floor(ncols) || nrows != std::floor(nrows) || ncols < 0 || nrows < 0) {
    throw input_error(path + ": ncols and nrows must be non-negative integers");
  }
  if (ncols > 1e9 || nrows > 1e9) {  // before the conversion to an integer can overflow
    throw input_error(path + ": ncols " + format_number(ncols) + " x nrows " +
                      format_number(nrows) + " is far beyond the size limit");
  }
  check_terrain_size(path, static_cast<long long>(ncols), static_cast<long long>(nrows));
  const double cell = header["cellsize"];
  if (!(cell >= kMinCell && cell <= kMaxCell)) {
    throw input_error(path + ": cellsize " + format_number(cell) + " is outside " +
                      format_number(kMinCell) + " to " + format_number(kMaxCell) + " m");
  }

  Heightmap terrain(static_cast<int>(ncols), static_cast<int>(nrows), cell);
  const double half = header.count("xllcenter") ? 0.5 * cell : 0.0;
  terrain.origin_x = header.count("xllcenter") ? header["xllcenter"] - half : header["xllcorner"];
  terrain.origin_z = header.count("yllcenter") ? header["yllcenter"] - half : header["yllcorner"];
  const bool has_nodata = header.count("nodata_value") > 0;
  const double nodata_value = has_nodata ? header["nodata_value"] : 0.0;
  if (has_nodata) terrain.georef.nodata = nodata_value;  // written back as the rasters' own

  long long holes = 0;
  const long long expected = static_cast<long long>(terrain.size());
  for (long long k = 0; k < expected; ++k) {
    if (!tokens.next(value)) {
      throw input_error(path + ": truncated: expected " + std::to_string(expected) + " heights (" +
                        std::to_string(terrain.nx) + " x " + std::to_string(terrain.ny) +
                        "), found " + std::to_string(k));
    }
    double v = 0.0;
    if (!parse_double(value, v)) {
      throw input_error(path + ": line " + std::to_string(tokens.line()) + ": non-numeric height " +
                        quoted(value));
    }
    if (has_nodata && v == nodata_value) {
      ++holes;
      terrain.h[k] = std::nanf("");
      continue;
    }
    if (!(std::fabs(v) <= kMaxAbsHeight)) {
      throw input_error(path + ": line " + std::to_string(tokens.line()) + ": height " +
                        quoted(value) + " is not a finite number within ±" +
                        format_number(kMaxAbsHeight) + " m");
    }
    terrain.h[k] = static_cast<float>(v);
  }
  if (tokens.next(value)) {
    throw input_error(path + ": line " + std::to_string(tokens.line()) +
                      ": more values than ncols x nrows = " + std::to_string(expected));
  }
  apply_nodata_policy(path, terrain, holes, nodata);
  return terrain;
}

void write_asc(const std::string& path, const Heightmap& terrain) {
  const float nodata = static_cast<float>(terrain.georef.nodata.value_or(-9999.0));
  write_file_atomically(path, [&](std::FILE* f) {
    std::fprintf(f,
                 "ncols %d\nnrows %d\nxllcorner %.17g\nyllcorner %.17g\ncellsize "
                 "%.17g\nNODATA_value %.9g\n",
                 terrain.nx, terrain.ny, terrain.origin_x, terrain.origin_z, terrain.cell,
                 static_cast<double>(nodata));
    // %.9g round-trips every float exactly.
    const std::vector<float> h = heights_with_holes(terrain, nodata);
    for (int j = 0; j < terrain.ny; ++j) {
      for (int i = 0; i < terrain.nx; ++i) {
        std::fprintf(f, i + 1 < terrain.nx ? "%.9g " : "%.9g\n",
                     static_cast<double>(h[static_cast<std::size_t>(j) * terrain.nx + i]));
      }
    }
    if (std::ferror(f)) throw runtime_error(path + ": write failed");
  });
}

}  // namespace runnel
