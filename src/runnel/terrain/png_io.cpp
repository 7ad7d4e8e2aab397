// SPDX-License-Identifier: MIT
// 16-bit grayscale PNG heightmaps. Heights map linearly onto 0..65535 through a range [min, max];
// runnel stores that range (and the cell size) in tEXt chunks so its own files read back in metres.
// A PNG without them reads as raw sample values in metres unless a range is given.
#include <png.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "runnel/core/error.hpp"
#include "runnel/io/atomic_file.hpp"
#include "runnel/terrain/terrain_io.hpp"

namespace runnel {
namespace {

constexpr const char* kRangeKey = "runnel.height_range";
constexpr const char* kCellKey = "runnel.cell_size";

struct PngErrorState {
  char message[256] = {0};
};

void on_png_error(png_structp png, png_const_charp msg) {
  auto* state = static_cast<PngErrorState*>(png_get_error_ptr(png));
  std::snprintf(state->message, sizeof(state->message), "%s", msg);
  png_longjmp(png, 1);
}
void on_png_warning(png_structp, png_const_charp) {}

// Everything libpng touches lives here, so nothing with a destructor is live across setjmp.
struct PngReadResult {
  png_uint_32 width = 0, height = 0;
  int bit_depth = 0, color_type = 0;
  // The runnel tEXt chunks as written; parsed strictly once libpng is done.
  bool has_range = false, has_cell = false;
  std::string range_text, cell_text;
  // Buffers live in the caller's object so a longjmp out of libpng skips no destructor.
  std::vector<png_byte> row;
};

// Returns an empty string on success, else libpng's message. `samples` is filled by the second
// call.
std::string png_read(std::FILE* f, PngReadResult& r, std::vector<std::uint16_t>* samples) {
  PngErrorState errors;
  png_structp png =
      png_create_read_struct(PNG_LIBPNG_VER_STRING, &errors, on_png_error, on_png_warning);
  if (!png) return "out of memory";
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return errors.message[0] ? errors.message : "corrupt PNG";
  }
  png_init_io(png, f);
  // Limits before libpng reads anything: the image within runnel's terrain limits, and no
  // ancillary chunk (text, ICC profile) inflating to more than 4 MiB.
  png_set_user_limits(png, kMaxSide, kMaxSide);
  png_set_chunk_malloc_max(png, 4u << 20);
  png_set_chunk_cache_max(png, 1000);
  png_read_info(png, info);
  r.width = png_get_image_width(png, info);
  r.height = png_get_image_height(png, info);
  r.bit_depth = png_get_bit_depth(png, info);
  r.color_type = png_get_color_type(png, info);
  png_textp text = nullptr;
  int num_text = 0;
  png_get_text(png, info, &text, &num_text);
  for (int t = 0; t < num_text; ++t) {
    if (std::strcmp(text[t].key, kRangeKey) == 0) {
      r.has_range = true;
      r.range_text.assign(text[t].text, std::min<std::size_t>(text[t].text_length, 200));
    } else if (std::strcmp(text[t].key, kCellKey) == 0) {
      r.has_cell = true;
      r.cell_text.assign(text[t].text, std::min<std::size_t>(text[t].text_length, 200));
    }
  }
  if (samples) {
    if (r.color_type != PNG_COLOR_TYPE_GRAY || (r.bit_depth != 16 && r.bit_depth != 8)) {
      png_destroy_read_struct(&png, &info, nullptr);
      return "not a grayscale PNG (need 8- or 16-bit gray, found colour type " +
             std::to_string(r.color_type) + " at " + std::to_string(r.bit_depth) + " bits)";
    }
    if (r.bit_depth == 16) png_set_swap(png);  // PNG is big-endian; we read native uint16
    if (png_get_interlace_type(png, info) != PNG_INTERLACE_NONE) {
      png_destroy_read_struct(&png, &info, nullptr);
      return "interlaced (Adam7) PNGs are not read; save the heightmap non-interlaced";
    }
    png_read_update_info(png, info);
    // Row by row, the samples growing as rows actually decode: a header that claims a huge image
    // over a few bytes of data fails at its first missing row, not at a huge allocation.
    r.row.resize(png_get_rowbytes(png, info));
    samples->clear();
    for (png_uint_32 y = 0; y < r.height; ++y) {
      png_read_row(png, r.row.data(), nullptr);
      for (png_uint_32 x = 0; x < r.width; ++x) {
        std::uint16_t v = r.row[x];
        if (r.bit_depth == 16) std::memcpy(&v, r.row.data() + 2 * x, 2);
        samples->push_back(v);
      }
    }
    png_read_end(png, nullptr);
  }
  png_destroy_read_struct(&png, &info, nullptr);
  return "";
}

// Whitespace-separated finite numbers, the whole text and nothing else ("1 2abc" is not).
bool parse_numbers(const std::string& text, std::vector<double>& out) {
  out.clear();
  std::size_t at = 0;
  while (at < text.size()) {
    while (at < text.size() && std::isspace(static_cast<unsigned char>(text[at]))) ++at;
    if (at == text.size()) break;
    double v = 0;
    const auto [p, ec] = std::from_chars(text.data() + at, text.data() + text.size(), v);
    if (ec != std::errc() || !std::isfinite(v)) return false;
    at = static_cast<std::size_t>(p - text.data());
    if (at < text.size() && !std::isspace(static_cast<unsigned char>(text[at]))) return false;
    out.push_back(v);
  }
  return !out.empty();
}

// Walks the chunk list before libpng sees the file: every chunk must lie inside the file. (libpng
// allocates a text chunk's claimed length, up to 2 GiB, before it finds the data missing.)
// Returns "" or what is wrong.
std::string check_chunks(std::FILE* f) {
  if (std::fseek(f, 0, SEEK_END) != 0) return "cannot seek";
  const long size = std::ftell(f);
  long at = 8;  // after the signature
  while (at + 12 <= size) {
    unsigned char header[8];
    if (std::fseek(f, at, SEEK_SET) != 0 || std::fread(header, 1, 8, f) != 8) return "truncated";
    const std::uint32_t length =
        (std::uint32_t{header[0]} << 24) | (header[1] << 16) | (header[2] << 8) | header[3];
    const std::string type(reinterpret_cast<const char*>(header + 4), 4);
    if (static_cast<long long>(at) + 12 + length > size) {
      return "chunk " + quoted(type) + " claims " + std::to_string(length) +
             " bytes, past the end of the file";
    }
    if (type == "IEND") return "";
    at += 12 + static_cast<long>(length);
  }
  return "no IEND chunk (truncated)";
}

}  // namespace

Heightmap read_png16(const std::string& path, const std::optional<HeightRange>& range,
                     double cell_if_none) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw input_error(path + ": cannot open for reading");
  unsigned char signature[8] = {0};
  if (std::fread(signature, 1, 8, f) != 8 || png_sig_cmp(signature, 0, 8) != 0) {
    std::fclose(f);
    throw input_error(path + ": not a PNG file");
  }
  std::string err = check_chunks(f);
  std::rewind(f);
  PngReadResult header;
  if (err.empty()) err = png_read(f, header, nullptr);
  if (err.empty()) {
    try {
      check_terrain_size(path, header.width, header.height);
    } catch (...) {
      std::fclose(f);
      throw;
    }
    std::rewind(f);
  }
  std::vector<std::uint16_t> samples;
  if (err.empty()) err = png_read(f, header, &samples);
  std::fclose(f);
  if (!err.empty()) throw input_error(path + ": corrupt or unsupported PNG: " + err);

  const double max_sample = header.bit_depth == 16 ? 65535.0 : 255.0;
  double lo = 0.0, hi = max_sample;  // raw sample values in metres
  std::vector<double> numbers;
  if (header.has_range && (!parse_numbers(header.range_text, numbers) || numbers.size() != 2)) {
    throw input_error(path + ": tEXt " + kRangeKey + " " + quoted(header.range_text) +
                      " is not two numbers MIN MAX");
  }
  if (range) {
    lo = range->min;
    hi = range->max;
  } else if (header.has_range) {
    lo = numbers[0];
    hi = numbers[1];
  }
  check_height_range(path, {lo, hi});
  double cell = cell_if_none;
  if (header.has_cell) {
    if (!parse_numbers(header.cell_text, numbers) || numbers.size() != 1 ||
        !(numbers[0] >= kMinCell && numbers[0] <= kMaxCell)) {
      throw input_error(path + ": tEXt " + kCellKey + " " + quoted(header.cell_text) +
                        " is not a cell size of " + format_number(kMinCell) + " to " +
                        format_number(kMaxCell) + " m");
    }
    cell = numbers[0];
  }
  Heightmap terrain(static_cast<int>(header.width), static_cast<int>(header.height), cell);
  for (std::size_t k = 0; k < samples.size(); ++k) {
    terrain.h[k] = static_cast<float>(lo + (hi - lo) * (samples[k] / max_sample));
  }
  return terrain;
}

void write_png16(const std::string& path, const Heightmap& terrain,
                 const std::optional<HeightRange>& range) {
  double lo = terrain.min_height(), hi = terrain.max_height();
  if (range) {
    lo = range->min;
    hi = range->max;
  }
  if (!(hi > lo)) hi = lo + 1.0;  // a flat terrain still gets a valid range
  std::vector<std::uint16_t> samples(terrain.size());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const double t = (terrain.h[k] - lo) / (hi - lo);
    samples[k] = static_cast<std::uint16_t>(std::lround(std::clamp(t, 0.0, 1.0) * 65535.0));
  }
  std::ostringstream range_text, cell_text;
  range_text.precision(17);
  cell_text.precision(17);
  range_text << lo << " " << hi;
  cell_text << terrain.cell;
  const std::string range_str = range_text.str(), cell_str = cell_text.str();

  write_file_atomically(path, [&](std::FILE* f) {
    PngErrorState errors;
    png_structp png =
        png_create_write_struct(PNG_LIBPNG_VER_STRING, &errors, on_png_error, on_png_warning);
    if (!png) throw runtime_error(path + ": out of memory");
    png_infop info = png_create_info_struct(png);
    std::vector<png_bytep> rows(terrain.ny);
    std::vector<png_byte> bytes(samples.size() * 2);
    for (std::size_t k = 0; k < samples.size(); ++k) {  // big-endian, as PNG stores 16-bit samples
      bytes[2 * k] = static_cast<png_byte>(samples[k] >> 8);
      bytes[2 * k + 1] = static_cast<png_byte>(samples[k] & 0xff);
    }
    for (int y = 0; y < terrain.ny; ++y)
      rows[y] = bytes.data() + static_cast<std::size_t>(y) * terrain.nx * 2;
    png_text text[2];
    std::memset(text, 0, sizeof(text));
    text[0].compression = PNG_TEXT_COMPRESSION_NONE;
    text[0].key = const_cast<char*>(kRangeKey);
    text[0].text = const_cast<char*>(range_str.c_str());
    text[1].compression = PNG_TEXT_COMPRESSION_NONE;
    text[1].key = const_cast<char*>(kCellKey);
    text[1].text = const_cast<char*>(cell_str.c_str());
    volatile bool failed = false;
    if (setjmp(png_jmpbuf(png))) {
      failed = true;
    } else {
      png_init_io(png, f);
      png_set_IHDR(png, info, terrain.nx, terrain.ny, 16, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
                   PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
      png_set_text(png, info, text, 2);
      png_write_info(png, info);
      png_write_image(png, rows.data());
      png_write_end(png, nullptr);
    }
    png_destroy_write_struct(&png, &info);
    if (failed) throw runtime_error(path + ": PNG write failed: " + errors.message);
  });
}

}  // namespace runnel
