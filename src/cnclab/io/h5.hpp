#pragma once
// A thin RAII layer over the HDF5 C API: one File with path-addressed
// datasets ("/model/parameters") and attributes. Parent groups are created on
// write. Every failure is an IoError naming the file and the object:
// "results/x.h5: /model/parameters: cannot read dataset (not found)".
//
// Matrix convention: an Eigen::MatrixXd with one sample per column
// (features x samples, column-major) is stored as a 2-D dataset of shape
// (samples, features) in C order - the same bytes, so h5py reads (N, d).
#include <hdf5.h>

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace cnclab {

// Owns one hid_t and closes it with the matching H5*close.
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

 private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

class H5File {
 public:
  // Creates (truncating) a file for writing.
  static H5File create(const std::filesystem::path& path);
  // Opens an existing file read-only; missing or not HDF5 -> IoError.
  static H5File open_read(const std::filesystem::path& path);

  const std::filesystem::path& path() const { return path_; }

  // --- writing (parents created as needed; `units` added when non-empty)
  void write_vector(const std::string& name, std::span<const double> values,
                    const std::string& units = "");
  void write_indices(const std::string& name, const std::vector<std::size_t>& values);
  void write_matrix(const std::string& name, const Eigen::MatrixXd& m,
                    const std::string& units = "");
  void write_string(const std::string& name, const std::string& text);
  void write_strings(const std::string& name, const std::vector<std::string>& texts);
  void create_group(const std::string& name);
  void set_attribute(const std::string& object, const std::string& attr, double value);
  void set_attribute(const std::string& object, const std::string& attr, std::int64_t value);
  void set_attribute(const std::string& object, const std::string& attr, const std::string& value);
  void set_attribute(const std::string& object, const std::string& attr, const char* value) {
    set_attribute(object, attr, std::string(value));
  }
  // Flushes all buffers of the file to the OS.
  void flush();
  // Closes the file (also done by the destructor); errors surface here.
  void close();

  // --- reading
  bool exists(const std::string& name) const;
  bool has_attribute(const std::string& object, const std::string& attr) const;
  std::vector<double> read_vector(const std::string& name) const;
  std::vector<std::size_t> read_indices(const std::string& name) const;
  Eigen::MatrixXd read_matrix(const std::string& name) const;
  std::string read_string(const std::string& name) const;
  std::vector<std::string> read_strings(const std::string& name) const;
  double attribute_double(const std::string& object, const std::string& attr) const;
  std::int64_t attribute_int(const std::string& object, const std::string& attr) const;
  std::string attribute_string(const std::string& object, const std::string& attr) const;
  std::vector<std::string> attribute_names(const std::string& object) const;
  // Names of the links in a group, in HDF5's name order.
  std::vector<std::string> children(const std::string& group) const;

 private:
  H5File(std::filesystem::path path, H5Handle file);
  [[noreturn]] void fail(const std::string& object, const std::string& what) const;
  H5Handle open_dataset(const std::string& name) const;
  H5Handle open_object(const std::string& name) const;
  H5Handle open_attribute(const std::string& object, const std::string& attr) const;
  std::vector<hsize_t> dims(hid_t dataset, const std::string& name, int rank) const;
  H5Handle create_dataset(const std::string& name, hid_t type, const std::vector<hsize_t>& dims);
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
