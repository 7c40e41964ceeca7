#pragma once
// A thin RAII layer over the HDF5 C API: one H5File with path-addressed
// datasets ("/model/parameters") and attributes; groups are addressed by path
// too (no separate group object: every call names the full path, which is
// also what error messages and h5py users see). Parent groups are created on
// write. Every failure is an IoError naming the file and the object:
// "results/x.h5: /model/parameters: cannot read dataset (not found)".
//
// Matrix convention: an Eigen::MatrixXd with one sample per column
// (features x samples, column-major) is stored as a 2-D dataset of shape
// (samples, features) in C order - the same bytes, so h5py reads (N, d).
//
// Stored types: float64 little-endian for doubles, int64 / uint64 little-endian
// for integers, fixed-length null-padded UTF-8 for strings (never
// variable-length: see h5.cpp; strings must not contain NUL bytes). Readers
// check rank, shape and type class (integer, floating point, string) and
// convert within a class; a value of another class is an IoError, never a
// silent conversion.
//
// Numeric datasets carry a `units` attribute when given one ("mm", "µm",
// "1" for dimensionless).
//
// HDF5 prints its error stack to stderr by default. Every H5File entry point
// turns that off for the calling thread (the setting is per thread in the
// thread-safe libhdf5 Debian ships), so errors reach the user only as IoError.
#include <hdf5.h>

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace cnclab {

// Owns one hid_t and closes it with the matching H5*close. Move-only.
class H5Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  H5Handle() = default;
  H5Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  ~H5Handle() { reset(); }
  H5Handle(H5Handle&& other) noexcept : id_(other.id_), closer_(other.closer_) { other.id_ = -1; }
  H5Handle& operator=(H5Handle&& other) noexcept;
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  void reset();
  // Gives up ownership without closing.
  hid_t release() {
    const hid_t id = id_;
    id_ = -1;
    return id;
  }

 private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

// One open HDF5 file. Move-only; the destructor closes it (errors on that
// path are lost: call close() to see them).
class H5File {
 public:
  // Creates (truncating) a file for writing.
  static H5File create(const std::filesystem::path& path);
  // Opens an existing file read-only; missing, unreadable, not HDF5 or
  // truncated -> IoError.
  static H5File open_read(const std::filesystem::path& path);

  H5File(H5File&&) noexcept = default;
  H5File& operator=(H5File&&) noexcept = default;
  ~H5File();

  const std::filesystem::path& path() const { return path_; }

  // --- writing (parents created as needed; `units` added when non-empty;
  // writing an existing dataset name is an IoError)
  void write_vector(const std::string& name, std::span<const double> values,
                    const std::string& units = "");
  void write_int64s(const std::string& name, std::span<const std::int64_t> values,
                    const std::string& units = "");
  void write_uint64s(const std::string& name, std::span<const std::uint64_t> values,
                     const std::string& units = "");
  // Sample indices (split parts) as uint64.
  void write_indices(const std::string& name, const std::vector<std::size_t>& values);
  // Shape (m.cols(), m.rows()): see the matrix convention above.
  void write_matrix(const std::string& name, const Eigen::MatrixXd& m,
                    const std::string& units = "");
  // Scalar (rank-0) datasets.
  void write_double(const std::string& name, double value, const std::string& units = "");
  void write_int(const std::string& name, std::int64_t value, const std::string& units = "");
  // One UTF-8 string (e.g. YAML text) as a scalar dataset; a list as 1-D.
  void write_string(const std::string& name, const std::string& text);
  void write_strings(const std::string& name, const std::vector<std::string>& texts);
  // Creates the group and its parents; an existing group is kept.
  void create_group(const std::string& name);
  // Attributes are scalars; setting an existing one replaces it.
  void set_attribute(const std::string& object, const std::string& attr, double value);
  void set_attribute(const std::string& object, const std::string& attr, std::int64_t value);
  void set_attribute(const std::string& object, const std::string& attr, const std::string& value);
  void set_attribute(const std::string& object, const std::string& attr, const char* value) {
    set_attribute(object, attr, std::string(value));
  }
  // The `units` attribute of a dataset.
  void set_units(const std::string& name, const std::string& units) {
    set_attribute(name, "units", units);
  }
  // Flushes all buffers of the file to the OS.
  void flush();
  // Closes the file (also done by the destructor); errors surface here.
  void close();

  // --- reading
  // True if every link of the path exists ("/" always does; "" never).
  bool exists(const std::string& name) const;
  bool is_group(const std::string& name) const;
  bool has_attribute(const std::string& object, const std::string& attr) const;
  std::vector<double> read_vector(const std::string& name) const;
  // Integers of either signedness; a value out of range of the result is an IoError.
  std::vector<std::int64_t> read_int64s(const std::string& name) const;
  std::vector<std::uint64_t> read_uint64s(const std::string& name) const;
  std::vector<std::size_t> read_indices(const std::string& name) const;
  Eigen::MatrixXd read_matrix(const std::string& name) const;
  double read_double(const std::string& name) const;
  std::int64_t read_int(const std::string& name) const;
  std::string read_string(const std::string& name) const;
  std::vector<std::string> read_strings(const std::string& name) const;
  double attribute_double(const std::string& object, const std::string& attr) const;
  std::int64_t attribute_int(const std::string& object, const std::string& attr) const;
  std::string attribute_string(const std::string& object, const std::string& attr) const;
  // The `units` attribute of a dataset; IoError when it has none.
  std::string units(const std::string& name) const { return attribute_string(name, "units"); }
  std::vector<std::string> attribute_names(const std::string& object) const;
  // Names of the links in a group, in HDF5's name order.
  std::vector<std::string> children(const std::string& group) const;

 private:
  H5File(std::filesystem::path path, H5Handle file);
  [[noreturn]] void fail(const std::string& object, const std::string& what) const;
  H5Handle open_dataset(const std::string& name) const;
  H5Handle open_object(const std::string& name) const;
  H5Handle open_attribute(const std::string& object, const std::string& attr) const;
  // Opens a dataset of type class `cls` and rank `rank` (0 = scalar) whose
  // stored bytes can hold its declared shape; returns it and its shape.
  H5Handle open_array(const std::string& name, H5T_class_t cls, int rank,
                      std::vector<hsize_t>& shape) const;
  std::vector<hsize_t> dims(hid_t dataset, const std::string& name, int rank) const;
  void check_stored_size(hid_t dataset, const std::string& name, double bytes) const;
  H5Handle create_dataset(const std::string& name, hid_t type, const std::vector<hsize_t>& dims);
  void write_numeric(const std::string& name, hid_t file_type, hid_t memory_type,
                     const std::vector<hsize_t>& dims, const void* data, bool empty,
                     const std::string& units);
  // An integer dataset of rank `rank` (0 = scalar), read as int64 bits when
  // stored signed (is_signed = true), else as uint64.
  std::vector<std::uint64_t> read_integer_bits(const std::string& name, int rank,
                                               bool& is_signed) const;
  std::vector<std::int64_t> read_int64s(const std::string& name, int rank) const;
  std::vector<std::uint64_t> read_uint64s(const std::string& name, int rank) const;
  // The in-memory type to read a stored fixed-length string type with;
  // IoError for variable-length or absurd lengths.
  H5Handle fixed_string_type(hid_t stored, const std::string& object) const;

  // Largest string (or string list) read: results hold YAML text of a few KiB.
  static constexpr std::size_t kMaxStringBytes = std::size_t{64} << 20;

  std::filesystem::path path_;
  H5Handle file_;
};

// "1.10.8": the version of the HDF5 library linked in.
std::string hdf5_version();

}  // namespace cnclab
