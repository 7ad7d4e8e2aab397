// SPDX-License-Identifier: MIT
#pragma once
#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

namespace runnel {

// A small RAII layer over the HDF5 C API for runnel's files: groups, typed datasets (chunked and
// deflate-compressed where large), attributes. Every failure throws runnel::Error naming the file
// and the object (exit code 2 when reading, 1 when writing).
class H5Handle {
 public:
  H5Handle() = default;
  H5Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  H5Handle(H5Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  H5Handle& operator=(H5Handle&& o) noexcept;
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  ~H5Handle();
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_ = -1;
  herr_t (*close_)(hid_t) = nullptr;
};

class H5File {
 public:
  // Opens for reading (validates that it is an HDF5 file) or creates a new file.
  static H5File open_read(const std::string& path);
  static H5File create(const std::string& path);
  void flush();

  const std::string& path() const { return path_; }
  hid_t id() const { return file_.get(); }

  // Writing. `dims` is {n} or {rows, cols}.
  void create_group(const std::string& name);
  void write(const std::string& name, const std::vector<float>& data,
             const std::vector<hsize_t>& dims);
  void write(const std::string& name, const std::vector<double>& data,
             const std::vector<hsize_t>& dims);
  void write(const std::string& name, const std::vector<std::int64_t>& data,
             const std::vector<hsize_t>& dims);
  void write(const std::string& name, const std::vector<std::int32_t>& data,
             const std::vector<hsize_t>& dims);
  void write(const std::string& name, const std::vector<std::uint32_t>& data,
             const std::vector<hsize_t>& dims);
  void attribute(const std::string& object, const std::string& name, double value);
  void attribute(const std::string& object, const std::string& name, std::int64_t value);
  void attribute(const std::string& object, const std::string& name, const std::string& value);
  // A text as a scalar fixed-length string dataset: no size limit (an attribute's is 64 KiB).
  void write_text(const std::string& name, const std::string& text);
  std::string read_text(const std::string& name) const;

  // Reading; `expected` (if not empty) must equal the dataset's dimensions.
  std::vector<hsize_t> dims(const std::string& name) const;
  bool exists(const std::string& name) const;
  bool has_attribute(const std::string& object, const std::string& name) const;
  // Whether a dataset holds integers (else floating point).
  bool is_integer(const std::string& name) const;
  std::vector<float> read_float(const std::string& name,
                                const std::vector<hsize_t>& expected = {}) const;
  std::vector<double> read_double(const std::string& name,
                                  const std::vector<hsize_t>& expected = {}) const;
  std::vector<std::int64_t> read_int64(const std::string& name,
                                       const std::vector<hsize_t>& expected = {}) const;
  std::vector<std::int32_t> read_int32(const std::string& name,
                                       const std::vector<hsize_t>& expected = {}) const;
  std::vector<std::uint32_t> read_uint32(const std::string& name,
                                         const std::vector<hsize_t>& expected = {}) const;
  double read_double_attribute(const std::string& object, const std::string& name) const;
  std::int64_t read_int_attribute(const std::string& object, const std::string& name) const;
  std::string read_string_attribute(const std::string& object, const std::string& name) const;

  // An extendable 3-D float dataset (frames × rows × cols) that frames are appended to.
  void append_frame(const std::string& name, const std::vector<float>& frame, hsize_t rows,
                    hsize_t cols);

 private:
  template <typename T>
  void write_typed(const std::string& name, const std::vector<T>& data,
                   const std::vector<hsize_t>& dims, hid_t type);
  template <typename T>
  std::vector<T> read_typed(const std::string& name, const std::vector<hsize_t>& expected,
                            hid_t type) const;
  // The dataset `name`, or a refusal that says whether it is absent or there but unreadable.
  H5Handle open_dataset(const std::string& name) const;
  std::string path_;
  H5Handle file_;
  bool reading_ = false;
};

}  // namespace runnel
