// SPDX-License-Identifier: MIT
// NumPy .npy arrays (format versions 1.0 to 3.0): a 2-D float32 or float64 array of shape
// (rows, columns) = (ny, nx), C or Fortran order, either byte order. The format carries no cell
// size.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "runnel/core/error.hpp"
#include "runnel/io/atomic_file.hpp"
#include "runnel/terrain/terrain_io.hpp"

namespace runnel {
namespace {

constexpr char kMagic[] = "\x93NUMPY";

template <typename T>
T byteswap_value(T v) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  std::reverse(b, b + sizeof(T));
  std::memcpy(&v, b, sizeof(T));
  return v;
}

// NumPy's own reader refuses longer headers (np.load's max_header_size); its writer pads to 64.
constexpr std::uint32_t kMaxHeaderBytes = 10000;

// The text after `'key':` in the header's dict literal (spaces skipped), for the caller to read
// its value from: a plain scan, so no header, however long or odd, can exhaust the stack.
std::string header_value(const std::string& header, const std::string& key,
                         const std::string& path) {
  const std::string quoted_key = "'" + key + "'";
  std::size_t at = header.find(quoted_key);
  if (at == std::string::npos) throw input_error(path + ": .npy header has no '" + key + "'");
  at = header.find_first_not_of(" \t", at + quoted_key.size());
  if (at == std::string::npos || header[at] != ':')
    throw input_error(path + ": .npy header's '" + key + "' has no value");
  at = header.find_first_not_of(" \t", at + 1);
  return at == std::string::npos ? std::string() : header.substr(at);
}

}  // namespace

namespace {

// What the header says about the array that follows it.
struct NpyArray {
  char byte_order = '<';
  int item_size = 4;
  bool fortran = false;
  long long ny = 0, nx = 0;
};

// The dict literal's text: after the magic, the version and the header's length, all checked
// against the file's size before anything is allocated.
std::string read_npy_header(std::ifstream& in, std::streamoff file_size, const std::string& path,
                            std::streamoff& data_start) {
  char prefix[8] = {0};
  if (file_size < 10 || !in.read(prefix, 8) || std::memcmp(prefix, kMagic, 6) != 0) {
    throw input_error(path + ": not a NumPy .npy file (bad magic)");
  }
  const int major = static_cast<unsigned char>(prefix[6]);
  std::uint32_t header_len = 0;
  std::streamoff header_start = 0;
  if (major == 1) {
    unsigned char len[2];
    in.read(reinterpret_cast<char*>(len), 2);
    header_len = len[0] | (len[1] << 8);
    header_start = 10;
  } else if (major == 2 || major == 3) {
    unsigned char len[4];
    in.read(reinterpret_cast<char*>(len), 4);
    header_len =
        len[0] | (len[1] << 8) | (len[2] << 16) | (static_cast<std::uint32_t>(len[3]) << 24);
    header_start = 12;
  } else {
    throw input_error(path + ": unsupported .npy format version " + std::to_string(major));
  }
  if (!in || header_start + header_len > file_size)
    throw input_error(path + ": truncated .npy header");
  if (header_len > kMaxHeaderBytes)
    throw input_error(path + ": .npy header of " + std::to_string(header_len) +
                      " bytes, more than the " + std::to_string(kMaxHeaderBytes) +
                      " NumPy itself reads");
  std::string header(header_len, '\0');
  in.read(header.data(), header_len);
  data_start = header_start + header_len;
  return header;
}

// Exactly two whole non-negative numbers, "(rows, columns)" with an optional trailing comma.
std::vector<long long> npy_shape(const std::string& header, const std::string& path) {
  const std::string shape_text = header_value(header, "shape", path);
  const auto shape_end = shape_text.find(')');
  if (!shape_text.starts_with("(") || shape_end == std::string::npos ||
      shape_text.find('(', 1) < shape_end)
    throw input_error(path + ": .npy header has no flat 'shape' tuple");
  std::vector<long long> shape;
  std::stringstream dims(shape_text.substr(1, shape_end - 1));
  for (std::string item; std::getline(dims, item, ',');) {
    const auto b = item.find_first_not_of(" \t"), e = item.find_last_not_of(" \t");
    if (b == std::string::npos) continue;  // the trailing comma of a 1-tuple
    const std::string digits = item.substr(b, e - b + 1);
    if (digits.size() > 12 || digits.find_first_not_of("0123456789") != std::string::npos) {
      throw input_error(path + ": .npy shape entry " + quoted(digits) +
                        " is not a non-negative integer of at most 12 digits");
    }
    shape.push_back(std::stoll(digits));
  }
  if (shape.size() != 2) {
    throw input_error(path + ": .npy array has " + std::to_string(shape.size()) +
                      " dimensions, expected 2 (rows, columns)");
  }
  return shape;
}

// The header is a Python dict literal, '{' ... '}', padded with spaces and a final newline.
NpyArray parse_npy_header(const std::string& header, const std::string& path) {
  const auto first = header.find_first_not_of(" \t");
  const auto last = header.find_last_not_of(" \t\n\0");
  if (first == std::string::npos || header[first] != '{' || header[last] != '}')
    throw input_error(path + ": .npy header is not a complete {...} dictionary");
  const std::string descr = header_value(header, "descr", path);
  if (descr.starts_with("["))
    throw input_error(path + ": .npy dtype is structured (fields), not float32 or float64");
  // '<f4', '>f8', '|f4' or '=f8': a byte order and a float's size.
  const bool is_float = descr.size() >= 5 && descr[0] == '\'' && descr[4] == '\'' &&
                        std::string_view("<>|=").find(descr[1]) != std::string_view::npos &&
                        descr[2] == 'f' && (descr[3] == '4' || descr[3] == '8');
  if (!is_float) {
    const auto close = descr.find('\'', 1);
    throw input_error(path + ": .npy dtype " +
                      quoted(descr.substr(1, close == std::string::npos ? 40 : close - 1)) +
                      " is not float32 or float64");
  }
  NpyArray a;
  a.byte_order = descr[1];
  a.item_size = descr[3] == '4' ? 4 : 8;
  const std::string order = header_value(header, "fortran_order", path);
  a.fortran = order.starts_with("True");
  if (!a.fortran && !order.starts_with("False"))
    throw input_error(path + ": .npy 'fortran_order' is neither True nor False");
  const std::vector<long long> shape = npy_shape(header, path);
  a.ny = shape[0];
  a.nx = shape[1];
  return a;
}

}  // namespace

Heightmap read_npy(const std::string& path, double cell_if_none, NodataPolicy nodata) {
  Heightmap terrain = read_npy_values(path, cell_if_none);
  long long holes = 0;
  for (float v : terrain.h) holes += std::isnan(v) ? 1 : 0;
  apply_nodata_policy(path, terrain, holes, nodata);  // NaN: the holes NPY writes
  return terrain;
}

Heightmap read_npy_values(const std::string& path, double cell_if_none) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw input_error(path + ": cannot open for reading");
  const std::streamoff file_size = in.tellg();
  in.seekg(0);
  std::streamoff data_start = 0;
  const NpyArray a = parse_npy_header(read_npy_header(in, file_size, path, data_start), path);
  const long long ny = a.ny, nx = a.nx;
  check_terrain_size(path, nx, ny);
  const std::streamoff data_bytes = static_cast<std::streamoff>(nx * ny * a.item_size);
  const std::streamoff available = file_size - data_start;
  if (available < data_bytes) {
    throw input_error(path + ": truncated: " + std::to_string(data_bytes) +
                      " bytes of data expected, " + std::to_string(available) + " present");
  }
  if (available > data_bytes)
    throw input_error(path + ": " + std::to_string(available - data_bytes) +
                      " bytes of trailing data");

  std::vector<char> raw(static_cast<std::size_t>(data_bytes));
  in.read(raw.data(), data_bytes);
  if (!in) throw input_error(path + ": read error");
  const bool swap = (a.byte_order == '>' && std::endian::native == std::endian::little) ||
                    (a.byte_order == '<' && std::endian::native == std::endian::big);

  Heightmap terrain(static_cast<int>(nx), static_cast<int>(ny), cell_if_none);
  for (long long k = 0; k < nx * ny; ++k) {
    double v = 0.0;
    if (a.item_size == 4) {
      float f;
      std::memcpy(&f, raw.data() + 4 * k, 4);
      v = swap ? byteswap_value(f) : f;
    } else {
      double d;
      std::memcpy(&d, raw.data() + 8 * k, 8);
      v = swap ? byteswap_value(d) : d;
    }
    // C order: k = row·nx + col. Fortran order: k = col·ny + row.
    const long long row = a.fortran ? k % ny : k / nx;
    const long long col = a.fortran ? k / ny : k % nx;
    terrain.h[static_cast<std::size_t>(row * nx + col)] = static_cast<float>(v);
  }
  return terrain;  // read_terrain checks the values, naming what they are
}

void write_npy(const std::string& path, const Heightmap& terrain) {
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" +
                       std::to_string(terrain.ny) + ", " + std::to_string(terrain.nx) + "), }";
  // Pad with spaces so that magic + length + header + '\n' is a multiple of 64 bytes.
  const std::size_t total = 10 + header.size() + 1;
  header.append((64 - total % 64) % 64, ' ');
  header.push_back('\n');
  write_file_atomically(path, [&](std::FILE* f) {
    std::fwrite(kMagic, 1, 6, f);
    const unsigned char version[2] = {1, 0};
    std::fwrite(version, 1, 2, f);
    const unsigned char len[2] = {static_cast<unsigned char>(header.size() & 0xff),
                                  static_cast<unsigned char>(header.size() >> 8)};
    std::fwrite(len, 1, 2, f);
    std::fwrite(header.data(), 1, header.size(), f);
    static_assert(std::endian::native == std::endian::little,
                  "the .npy writer assumes a little-endian host");
    // The holes (filled for the models) as NaN, NPY's only NODATA.
    const std::vector<float> h =
        heights_with_holes(terrain, std::numeric_limits<float>::quiet_NaN());
    std::fwrite(h.data(), sizeof(float), h.size(), f);
    if (std::ferror(f)) throw runtime_error(path + ": write failed");
  });
}

}  // namespace runnel
