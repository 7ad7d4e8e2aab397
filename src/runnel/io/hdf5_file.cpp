// SPDX-License-Identifier: MIT
#include "runnel/io/hdf5_file.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include <filesystem>

#include "runnel/core/error.hpp"
#include "runnel/core/input_file.hpp"

namespace runnel {
namespace {

// HDF5 prints its own error stack by default; runnel reports one line of its own instead.
void silence_hdf5() {
  static const bool silenced = [] {
    // No library shutdown at exit: after a write failed on a full disk, HDF5 keeps the file it
    // could not close, and closing it again from its atexit handler crashes (SIGSEGV in
    // H5F__close_cb). Every file runnel opens is closed by its H5File, so nothing is lost.
    H5dont_atexit();
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)silenced;
}

// libhdf5 1.10 follows a local heap's free list without a bound: a damaged file whose list loops
// back on itself makes a group lookup allocate list nodes until memory runs out (found by
// fuzz.checkpoint). Before HDF5 sees a file, each local heap ("HEAP", version 0, 8-byte lengths and
// addresses, as runnel writes) that lies inside the file has its free list walked here; a loop
// refuses the file. A heap header that does not parse is left to HDF5, which reports it.
void check_local_heaps(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return;
  std::fseek(f, 0, SEEK_END);
  const long file_size = std::ftell(f);
  const auto read_at = [&](long at, void* out, std::size_t n) {
    return at >= 0 && at + static_cast<long>(n) <= file_size && std::fseek(f, at, SEEK_SET) == 0 &&
           std::fread(out, 1, n, f) == n;
  };
  const auto u64 = [](const unsigned char* p) {
    std::uint64_t v = 0;
    for (int k = 7; k >= 0; --k) v = (v << 8) | p[k];
    return v;
  };
  std::vector<unsigned char> block(1 << 20);
  bool looping = false;
  for (long start = 0; start < file_size && !looping;
       start += static_cast<long>(block.size()) - 3) {
    const std::size_t n =
        std::min<std::size_t>(block.size(), static_cast<std::size_t>(file_size - start));
    if (!read_at(start, block.data(), n)) break;
    for (std::size_t i = 0; i + 4 <= n && !looping; ++i) {
      if (std::memcmp(block.data() + i, "HEAP", 4) != 0) continue;
      unsigned char header[32];
      const long at = start + static_cast<long>(i);
      if (!read_at(at, header, sizeof header) || header[4] != 0) continue;
      const std::uint64_t size = u64(header + 8), head = u64(header + 16), data = u64(header + 24);
      if (size > static_cast<std::uint64_t>(file_size) ||
          data > static_cast<std::uint64_t>(file_size) - size)
        continue;
      // H5HL_FREE_NULL (1) ends the list; every step moves to another block of at least 16 bytes.
      std::uint64_t offset = head;
      for (std::uint64_t steps = 0; offset != 1 && offset + 16 <= size; ++steps) {
        if (steps > size / 16) {
          looping = true;
          break;
        }
        unsigned char entry[8];
        if (!read_at(static_cast<long>(data + offset), entry, sizeof entry)) break;
        offset = u64(entry);
      }
    }
  }
  std::fclose(f);
  if (looping)
    throw input_error(path + ": damaged HDF5 file (a local heap's free list loops back on itself)");
}

std::string dims_text(const std::vector<hsize_t>& d) {
  std::string s;
  for (std::size_t k = 0; k < d.size(); ++k) s += (k ? " x " : "") + std::to_string(d[k]);
  return s.empty() ? "scalar" : s;
}

}  // namespace

H5Handle& H5Handle::operator=(H5Handle&& o) noexcept {
  if (this != &o) {
    if (id_ >= 0 && close_) close_(id_);
    id_ = o.id_;
    close_ = o.close_;
    o.id_ = -1;
  }
  return *this;
}

H5Handle::~H5Handle() {
  if (id_ >= 0 && close_) close_(id_);
}

H5File H5File::open_read(const std::string& path) {
  silence_hdf5();
  require_regular_input(path, "HDF5 file");
  if (H5Fis_hdf5(path.c_str()) <= 0) throw input_error(path + ": not an HDF5 file (or truncated)");
  check_local_heaps(path);
  H5File f;
  f.path_ = path;
  f.reading_ = true;
  f.file_ = H5Handle(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!f.file_.valid()) throw input_error(path + ": cannot open as HDF5 (corrupt or truncated)");
  return f;
}

H5File H5File::create(const std::string& path) {
  silence_hdf5();
  H5File f;
  f.path_ = path;
  f.file_ = H5Handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  if (!f.file_.valid()) throw runtime_error(path + ": cannot create HDF5 file");
  return f;
}

void H5File::flush() {
  if (H5Fflush(file_.get(), H5F_SCOPE_GLOBAL) < 0)
    throw runtime_error(path_ + ": HDF5 flush failed");
}

void H5File::create_group(const std::string& name) {
  H5Handle g(H5Gcreate2(file_.get(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
             H5Gclose);
  if (!g.valid()) throw runtime_error(path_ + ": cannot create group " + name);
}

template <typename T>
void H5File::write_typed(const std::string& name, const std::vector<T>& data,
                         const std::vector<hsize_t>& dims, hid_t type) {
  H5Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
  H5Handle props(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  hsize_t total = 1;
  for (auto d : dims) total *= d;
  if (total != data.size()) {
    throw runtime_error(path_ + ": dataset " + name + " has " + std::to_string(data.size()) +
                        " values for " + dims_text(dims));
  }
  // Chunk and compress what is large enough to pay for it.
  if (total >= 4096) {
    std::vector<hsize_t> chunk(dims);
    if (dims.size() == 1)
      chunk[0] = std::min<hsize_t>(dims[0], 65536);
    else
      for (auto& c : chunk) c = std::min<hsize_t>(c, 256);
    H5Pset_chunk(props.get(), static_cast<int>(chunk.size()), chunk.data());
    H5Pset_shuffle(props.get());
    H5Pset_deflate(props.get(), 4);
  }
  H5Handle set(H5Dcreate2(file_.get(), name.c_str(), type, space.get(), H5P_DEFAULT, props.get(),
                          H5P_DEFAULT),
               H5Dclose);
  if (!set.valid()) throw runtime_error(path_ + ": cannot create dataset " + name);
  if (total > 0 && H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0) {
    throw runtime_error(path_ + ": cannot write dataset " + name);
  }
}

void H5File::write(const std::string& n, const std::vector<float>& d,
                   const std::vector<hsize_t>& dims) {
  write_typed(n, d, dims, H5T_NATIVE_FLOAT);
}

void H5File::write(const std::string& n, const std::vector<double>& d,
                   const std::vector<hsize_t>& dims) {
  write_typed(n, d, dims, H5T_NATIVE_DOUBLE);
}
void H5File::write(const std::string& n, const std::vector<std::int64_t>& d,
                   const std::vector<hsize_t>& dims) {
  write_typed(n, d, dims, H5T_NATIVE_INT64);
}
void H5File::write(const std::string& n, const std::vector<std::int32_t>& d,
                   const std::vector<hsize_t>& dims) {
  write_typed(n, d, dims, H5T_NATIVE_INT32);
}
void H5File::write(const std::string& n, const std::vector<std::uint32_t>& d,
                   const std::vector<hsize_t>& dims) {
  write_typed(n, d, dims, H5T_NATIVE_UINT32);
}

namespace {

H5Handle open_object(const H5File& f, const std::string& object, bool reading) {
  H5Handle h(H5Oopen(f.id(), object.c_str(), H5P_DEFAULT), H5Oclose);
  if (!h.valid()) {
    const std::string msg = f.path() + ": missing " + object;
    throw reading ? input_error(msg) : runtime_error(msg);
  }
  return h;
}

}  // namespace

void H5File::attribute(const std::string& object, const std::string& name, double value) {
  H5Handle o = open_object(*this, object, false);
  H5Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  H5Handle a(
      H5Acreate2(o.get(), name.c_str(), H5T_NATIVE_DOUBLE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
      H5Aclose);
  if (!a.valid() || H5Awrite(a.get(), H5T_NATIVE_DOUBLE, &value) < 0) {
    throw runtime_error(path_ + ": cannot write attribute " + object + "@" + name);
  }
}

void H5File::attribute(const std::string& object, const std::string& name, std::int64_t value) {
  H5Handle o = open_object(*this, object, false);
  H5Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  H5Handle a(
      H5Acreate2(o.get(), name.c_str(), H5T_NATIVE_INT64, space.get(), H5P_DEFAULT, H5P_DEFAULT),
      H5Aclose);
  if (!a.valid() || H5Awrite(a.get(), H5T_NATIVE_INT64, &value) < 0) {
    throw runtime_error(path_ + ": cannot write attribute " + object + "@" + name);
  }
}

void H5File::attribute(const std::string& object, const std::string& name,
                       const std::string& value) {
  H5Handle o = open_object(*this, object, false);
  H5Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), std::max<std::size_t>(1, value.size()));
  H5Tset_strpad(type.get(), H5T_STR_NULLPAD);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  H5Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  H5Handle a(H5Acreate2(o.get(), name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
             H5Aclose);
  const std::string padded = value.empty() ? std::string(1, '\0') : value;
  if (!a.valid() || H5Awrite(a.get(), type.get(), padded.data()) < 0) {
    throw runtime_error(path_ + ": cannot write attribute " + object + "@" + name);
  }
}

void H5File::write_text(const std::string& name, const std::string& text) {
  H5Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), std::max<std::size_t>(1, text.size()));
  H5Tset_strpad(type.get(), H5T_STR_NULLPAD);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  H5Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  H5Handle d(H5Dcreate2(file_.get(), name.c_str(), type.get(), space.get(), H5P_DEFAULT,
                        H5P_DEFAULT, H5P_DEFAULT),
             H5Dclose);
  const std::string padded = text.empty() ? std::string(1, '\0') : text;
  if (!d.valid() || H5Dwrite(d.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, padded.data()) < 0)
    throw runtime_error(path_ + ": cannot write " + name);
}

std::string H5File::read_text(const std::string& name) const {
  H5Handle d(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!d.valid()) throw input_error(path_ + ": cannot open " + name);
  H5Handle type(H5Dget_type(d.get()), H5Tclose);
  H5Handle space(H5Dget_space(d.get()), H5Sclose);
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0 ||
      H5Sget_simple_extent_type(space.get()) != H5S_SCALAR)
    throw input_error(path_ + ": " + name + " is not a fixed-length string");
  const std::size_t size = H5Tget_size(type.get());
  if (size > (std::size_t{256} << 20))
    throw input_error(path_ + ": " + name + " claims " + std::to_string(size) +
                      " bytes, more than any runnel text");
  std::string out(size, '\0');
  if (H5Dread(d.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    throw input_error(path_ + ": unreadable " + name);
  while (!out.empty() && out.back() == '\0') out.pop_back();
  return out;
}

bool H5File::has_attribute(const std::string& object, const std::string& name) const {
  return H5Aexists_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT) > 0;
}

bool H5File::exists(const std::string& name) const {
  return H5Lexists(file_.get(), name.c_str(), H5P_DEFAULT) > 0;
}

// zlib's largest compression ratio (1032:1, for a long run of one byte) with a margin.
constexpr double kMaxDeflateRatio = 1100.0;

// A dataset whose header HDF5 cannot parse (a chunk dimension of 0, say) is named as damaged, not
// missing: whether libhdf5 1.10 refuses such a header or divides by it depends on what the process
// read before, so the message must not depend on which happened.
H5Handle H5File::open_dataset(const std::string& name) const {
  H5Handle set(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
  if (set.valid()) return set;
  if (!exists(name)) throw input_error(path_ + ": missing dataset " + name);
  throw input_error(path_ + ": damaged dataset " + name + " (its header cannot be read)");
}

std::vector<hsize_t> H5File::dims(const std::string& name) const {
  const H5Handle set = open_dataset(name);
  H5Handle space(H5Dget_space(set.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) throw input_error(path_ + ": unreadable dataset " + name);
  std::vector<hsize_t> d(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), d.data(), nullptr);
  return d;
}

bool H5File::is_integer(const std::string& name) const {
  const H5Handle set = open_dataset(name);
  H5Handle type(H5Dget_type(set.get()), H5Tclose);
  return H5Tget_class(type.get()) == H5T_INTEGER;
}

template <typename T>
std::vector<T> H5File::read_typed(const std::string& name, const std::vector<hsize_t>& expected,
                                  hid_t type) const {
  const std::vector<hsize_t> d = dims(name);
  if (!expected.empty() && d != expected) {
    throw input_error(path_ + ": dataset " + name + " is " + dims_text(d) + ", expected " +
                      dims_text(expected));
  }
  hsize_t total = 1;
  for (auto v : d) {
    // Refuse before allocating: a damaged header can claim terabytes.
    if (v > 0 && total > (hsize_t{1} << 32) / sizeof(T) / v)
      throw input_error(path_ + ": dataset " + name + " is " + dims_text(d) + ", too large");
    total *= v;
  }
  const H5Handle set = open_dataset(name);
  // The bytes the file really stores for the dataset bound what it can hold: deflate packs at
  // most about 1032 to 1. A small damaged file claiming gigabytes is refused before allocating.
  const double stored = static_cast<double>(H5Dget_storage_size(set.get()));
  if (static_cast<double>(total) * sizeof(T) > kMaxDeflateRatio * stored + (1 << 20))
    throw input_error(path_ + ": dataset " + name + " is " + dims_text(d) +
                      " but the file stores " + std::to_string(static_cast<long long>(stored)) +
                      " bytes of it (the file is damaged)");
  std::vector<T> out(total);
  if (total > 0 && H5Dread(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
    throw input_error(path_ + ": cannot read dataset " + name + " (corrupt or truncated)");
  }
  return out;
}

std::vector<float> H5File::read_float(const std::string& n, const std::vector<hsize_t>& e) const {
  return read_typed<float>(n, e, H5T_NATIVE_FLOAT);
}
std::vector<double> H5File::read_double(const std::string& n, const std::vector<hsize_t>& e) const {
  return read_typed<double>(n, e, H5T_NATIVE_DOUBLE);
}
std::vector<std::int64_t> H5File::read_int64(const std::string& n,
                                             const std::vector<hsize_t>& e) const {
  return read_typed<std::int64_t>(n, e, H5T_NATIVE_INT64);
}
std::vector<std::int32_t> H5File::read_int32(const std::string& n,
                                             const std::vector<hsize_t>& e) const {
  return read_typed<std::int32_t>(n, e, H5T_NATIVE_INT32);
}
std::vector<std::uint32_t> H5File::read_uint32(const std::string& n,
                                               const std::vector<hsize_t>& e) const {
  return read_typed<std::uint32_t>(n, e, H5T_NATIVE_UINT32);
}

namespace {

H5Handle open_attribute(const H5File& f, const std::string& object, const std::string& name) {
  H5Handle o = open_object(f, object, true);
  if (H5Aexists(o.get(), name.c_str()) <= 0)
    throw input_error(f.path() + ": missing attribute " + object + "@" + name);
  H5Handle a(H5Aopen(o.get(), name.c_str(), H5P_DEFAULT), H5Aclose);
  if (!a.valid()) throw input_error(f.path() + ": unreadable attribute " + object + "@" + name);
  return a;
}

}  // namespace

double H5File::read_double_attribute(const std::string& object, const std::string& name) const {
  H5Handle a = open_attribute(*this, object, name);
  double v = 0;
  if (H5Aread(a.get(), H5T_NATIVE_DOUBLE, &v) < 0)
    throw input_error(path_ + ": unreadable attribute " + name);
  return v;
}

std::int64_t H5File::read_int_attribute(const std::string& object, const std::string& name) const {
  H5Handle a = open_attribute(*this, object, name);
  std::int64_t v = 0;
  if (H5Aread(a.get(), H5T_NATIVE_INT64, &v) < 0)
    throw input_error(path_ + ": unreadable attribute " + name);
  return v;
}

std::string H5File::read_string_attribute(const std::string& object,
                                          const std::string& name) const {
  H5Handle a = open_attribute(*this, object, name);
  H5Handle type(H5Aget_type(a.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0) {
    throw input_error(path_ + ": attribute " + object + "@" + name +
                      " is not a fixed-length string");
  }
  // runnel's longest string attribute is the parameter set, a few kB: a damaged type may claim GB.
  const std::size_t size = H5Tget_size(type.get());
  if (size > (std::size_t{16} << 20)) {
    throw input_error(path_ + ": attribute " + object + "@" + name + " claims " +
                      std::to_string(size) + " bytes, more than any runnel string");
  }
  std::string out(size, '\0');
  if (H5Aread(a.get(), type.get(), out.data()) < 0)
    throw input_error(path_ + ": unreadable attribute " + name);
  while (!out.empty() && out.back() == '\0') out.pop_back();
  return out;
}

void H5File::append_frame(const std::string& name, const std::vector<float>& frame, hsize_t rows,
                          hsize_t cols) {
  if (!exists(name)) {
    const hsize_t dims[3] = {0, rows, cols}, max[3] = {H5S_UNLIMITED, rows, cols};
    H5Handle space(H5Screate_simple(3, dims, max), H5Sclose);
    H5Handle props(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    const hsize_t chunk[3] = {1, std::min<hsize_t>(rows, 256), std::min<hsize_t>(cols, 256)};
    H5Pset_chunk(props.get(), 3, chunk);
    H5Pset_shuffle(props.get());
    H5Pset_deflate(props.get(), 4);
    H5Handle set(H5Dcreate2(file_.get(), name.c_str(), H5T_NATIVE_FLOAT, space.get(), H5P_DEFAULT,
                            props.get(), H5P_DEFAULT),
                 H5Dclose);
    if (!set.valid()) throw runtime_error(path_ + ": cannot create dataset " + name);
  }
  H5Handle set(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
  H5Handle space(H5Dget_space(set.get()), H5Sclose);
  hsize_t dims[3];
  H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  if (dims[1] != rows || dims[2] != cols)
    throw runtime_error(path_ + ": " + name + " has another frame size");
  const hsize_t grown[3] = {dims[0] + 1, rows, cols};
  if (H5Dset_extent(set.get(), grown) < 0) throw runtime_error(path_ + ": cannot extend " + name);
  H5Handle file_space(H5Dget_space(set.get()), H5Sclose);
  const hsize_t start[3] = {dims[0], 0, 0}, count[3] = {1, rows, cols};
  H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr);
  H5Handle memory(H5Screate_simple(3, count, nullptr), H5Sclose);
  if (H5Dwrite(set.get(), H5T_NATIVE_FLOAT, memory.get(), file_space.get(), H5P_DEFAULT,
               frame.data()) < 0) {
    throw runtime_error(path_ + ": cannot append to " + name);
  }
  // On disk now, or an error now: a frame the disk had no room for must not pass silently.
  flush();
}

}  // namespace runnel
