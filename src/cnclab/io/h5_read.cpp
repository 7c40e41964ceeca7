// H5File reading: datasets (typed, shape- and size-checked) and attributes.
// File, structure and writing are in h5.cpp.
#include <algorithm>
#include <cstring>
#include <limits>

#include "cnclab/core/error.hpp"
#include "cnclab/core/resources.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/io/h5_detail.hpp"

namespace cnclab {
namespace {

// Bytes of `count` fixed-length strings of `length` into std::strings, each
// cut at its first NUL (null-padded or null-terminated).
std::vector<std::string> split_fixed(const std::vector<char>& bytes, std::size_t length,
                                     std::size_t count) {
  std::vector<std::string> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const char* p = bytes.data() + i * length;
    out.emplace_back(p, strnlen(p, length));
  }
  return out;
}

std::string class_name(H5T_class_t c) {
  switch (c) {
    case H5T_INTEGER:
      return "integer values";
    case H5T_FLOAT:
      return "floating-point values";
    case H5T_STRING:
      return "a string";
    default:
      return "values of HDF5 type class " + std::to_string(static_cast<int>(c));
  }
}

// "a scalar", "shape (3, 2)", "no data (null dataspace)".
std::string shape_text(hid_t space) {
  switch (H5Sget_simple_extent_type(space)) {
    case H5S_SCALAR:
      return "a scalar";
    case H5S_NULL:
      return "no data (null dataspace)";
    case H5S_SIMPLE: {
      const int rank = H5Sget_simple_extent_ndims(space);
      if (rank < 0 || rank > H5S_MAX_RANK) break;
      std::vector<hsize_t> d(static_cast<std::size_t>(rank));
      H5Sget_simple_extent_dims(space, d.data(), nullptr);
      std::string s = "shape (";
      for (std::size_t i = 0; i < d.size(); ++i) s += (i ? ", " : "") + std::to_string(d[i]);
      return s + ")";
    }
    default:
      break;
  }
  return "an unreadable dataspace";
}

std::string expected_text(int rank) {
  return rank == 0 ? std::string("a scalar") : "rank " + std::to_string(rank);
}

}  // namespace

// ---------------------------------------------------------------- reading

H5Handle H5File::open_dataset(const std::string& name) const {
  if (!exists(name)) fail(name, "cannot read dataset (not found)");
  H5Handle d = open_object(name);
  if (H5Iget_type(d.get()) != H5I_DATASET) fail(name, "cannot read dataset (not a dataset)");
  return d;
}

std::vector<hsize_t> H5File::dims(hid_t dataset, const std::string& name, int rank) const {
  const H5Handle space(H5Dget_space(dataset), H5Sclose);
  if (!space.valid()) fail(name, "cannot read the dataspace");
  const H5S_class_t kind = H5Sget_simple_extent_type(space.get());
  const bool ok = rank == 0 ? kind == H5S_SCALAR
                            : kind == H5S_SIMPLE && H5Sget_simple_extent_ndims(space.get()) == rank;
  if (!ok) fail(name, "expected " + expected_text(rank) + ", found " + shape_text(space.get()));
  std::vector<hsize_t> d(static_cast<std::size_t>(rank));
  if (rank > 0 && H5Sget_simple_extent_dims(space.get(), d.data(), nullptr) != rank) {
    fail(name, "cannot read the dataspace");
  }
  return d;
}

void H5File::check_stored_size(hid_t dataset, const std::string& name, double bytes) const {
  // Refuse a shape the stored bytes cannot hold before allocating for it: a
  // corrupt dataspace may declare 2^60 values. Unfiltered data need all
  // their bytes on disk. Deflate, the only filter default libhdf5 and h5py
  // builds write, expands at most 1032:1 (zlib "technical details"), so
  // 1100:1 bounds filtered data. Unwritten data (read as fill values) of up
  // to kSlack bytes are still read.
  constexpr double kSlack = 1 << 20;
  const H5Handle dcpl(H5Dget_create_plist(dataset), H5Pclose);
  const int filters = dcpl.valid() ? H5Pget_nfilters(dcpl.get()) : 0;
  const double stored = static_cast<double>(H5Dget_storage_size(dataset));
  if (bytes > stored * (filters > 0 ? 1100.0 : 1.0) + kSlack) {
    fail(name, "declares " + format_bytes(bytes) + " of data but stores " + format_bytes(stored) +
                   " (corrupt file?)");
  }
  try {
    check_memory(bytes, "reading the dataset");
  } catch (const ResourceError& e) {
    fail(name, e.what());
  }
}

H5Handle H5File::open_array(const std::string& name, H5T_class_t cls, int rank,
                            std::vector<hsize_t>& shape) const {
  H5Handle d = open_dataset(name);
  const H5Handle type(H5Dget_type(d.get()), H5Tclose);
  if (!type.valid()) fail(name, "cannot read the stored type");
  const H5T_class_t actual = H5Tget_class(type.get());
  if (actual != cls) fail(name, "expected " + class_name(cls) + ", found " + class_name(actual));
  shape = dims(d.get(), name, rank);
  double count = 1;
  for (const hsize_t n : shape) count *= static_cast<double>(n);
  // Memory holds at least 8 bytes per number; strings their stored length.
  const double element = static_cast<double>(std::max<std::size_t>(H5Tget_size(type.get()), 8));
  check_stored_size(d.get(), name, count * element);
  return d;
}

std::vector<double> H5File::read_vector(const std::string& name) const {
  std::vector<hsize_t> shape;
  const H5Handle d = open_array(name, H5T_FLOAT, 1, shape);
  std::vector<double> out(shape[0]);
  if (!out.empty() &&
      H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
    fail(name, "cannot read dataset");
  }
  return out;
}

Eigen::MatrixXd H5File::read_matrix(const std::string& name) const {
  std::vector<hsize_t> shape;
  const H5Handle d = open_array(name, H5T_FLOAT, 2, shape);
  Eigen::MatrixXd m(static_cast<Eigen::Index>(shape[1]), static_cast<Eigen::Index>(shape[0]));
  if (m.size() > 0 &&
      H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, m.data()) < 0) {
    fail(name, "cannot read dataset");
  }
  return m;
}

double H5File::read_double(const std::string& name) const {
  std::vector<hsize_t> shape;
  const H5Handle d = open_array(name, H5T_FLOAT, 0, shape);
  double v = 0;
  if (H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v) < 0) {
    fail(name, "cannot read dataset");
  }
  return v;
}

std::vector<std::uint64_t> H5File::read_integer_bits(const std::string& name, int rank,
                                                     bool& is_signed) const {
  std::vector<hsize_t> shape;
  const H5Handle d = open_array(name, H5T_INTEGER, rank, shape);
  const H5Handle type(H5Dget_type(d.get()), H5Tclose);
  is_signed = H5Tget_sign(type.get()) == H5T_SGN_2;
  std::vector<std::uint64_t> bits(rank == 0 ? 1 : shape[0]);
  if (!bits.empty() && H5Dread(d.get(), is_signed ? H5T_NATIVE_INT64 : H5T_NATIVE_UINT64, H5S_ALL,
                               H5S_ALL, H5P_DEFAULT, bits.data()) < 0) {
    fail(name, "cannot read dataset");
  }
  return bits;
}

std::vector<std::int64_t> H5File::read_int64s(const std::string& name, int rank) const {
  bool is_signed = false;
  const auto bits = read_integer_bits(name, rank, is_signed);
  constexpr auto kMax = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
  std::vector<std::int64_t> out(bits.size());
  for (std::size_t i = 0; i < bits.size(); ++i) {
    if (!is_signed && bits[i] > kMax) {
      fail(name, "value " + std::to_string(bits[i]) + " at index " + std::to_string(i) +
                     " exceeds the int64 range");
    }
    out[i] = static_cast<std::int64_t>(bits[i]);  // two's complement when stored signed
  }
  return out;
}

std::vector<std::uint64_t> H5File::read_uint64s(const std::string& name, int rank) const {
  bool is_signed = false;
  auto bits = read_integer_bits(name, rank, is_signed);
  for (std::size_t i = 0; is_signed && i < bits.size(); ++i) {
    const auto v = static_cast<std::int64_t>(bits[i]);
    if (v < 0) {
      fail(name, "negative value " + std::to_string(v) + " at index " + std::to_string(i) +
                     " where unsigned values are expected");
    }
  }
  return bits;
}

std::vector<std::int64_t> H5File::read_int64s(const std::string& name) const {
  return read_int64s(name, 1);
}

std::vector<std::uint64_t> H5File::read_uint64s(const std::string& name) const {
  return read_uint64s(name, 1);
}

std::vector<std::size_t> H5File::read_indices(const std::string& name) const {
  static_assert(sizeof(std::size_t) == sizeof(std::uint64_t));
  const auto v = read_uint64s(name, 1);
  return {v.begin(), v.end()};
}

std::int64_t H5File::read_int(const std::string& name) const {
  return read_int64s(name, 0).front();
}

H5Handle H5File::fixed_string_type(hid_t stored, const std::string& object) const {
  if (H5Tget_class(stored) != H5T_STRING) {
    fail(object, "expected a string, found " + class_name(H5Tget_class(stored)));
  }
  if (H5Tis_variable_str(stored) != 0) {
    fail(object, "variable-length strings are not read (cnclab writes fixed-length strings)");
  }
  const std::size_t length = H5Tget_size(stored);
  if (length == 0 || length > kMaxStringBytes) fail(object, "string length out of range");
  // Same character set as stored: libhdf5 does not convert between ASCII
  // (h5py's fixed-length default) and UTF-8; the bytes are taken as UTF-8.
  const H5T_cset_t cset = H5Tget_cset(stored);
  if (cset != H5T_CSET_ASCII && cset != H5T_CSET_UTF8) fail(object, "unknown character set");
  return h5_detail::string_type(length, cset);
}

std::string H5File::read_string(const std::string& name) const {
  std::vector<hsize_t> shape;
  const H5Handle d = open_array(name, H5T_STRING, 0, shape);
  const H5Handle stored(H5Dget_type(d.get()), H5Tclose);
  const H5Handle type = fixed_string_type(stored.get(), name);
  const std::size_t length = H5Tget_size(type.get());
  std::vector<char> bytes(length, '\0');
  if (H5Dread(d.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()) < 0) {
    fail(name, "cannot read string");
  }
  return split_fixed(bytes, length, 1).front();
}

std::vector<std::string> H5File::read_strings(const std::string& name) const {
  std::vector<hsize_t> shape;
  const H5Handle d = open_array(name, H5T_STRING, 1, shape);
  const auto n = shape[0];
  const H5Handle stored(H5Dget_type(d.get()), H5Tclose);
  const H5Handle type = fixed_string_type(stored.get(), name);
  const std::size_t length = H5Tget_size(type.get());
  if (n > kMaxStringBytes / length) fail(name, "string list too large");
  std::vector<char> bytes(length * n, '\0');
  if (n && H5Dread(d.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()) < 0) {
    fail(name, "cannot read strings");
  }
  return split_fixed(bytes, length, n);
}

// ---------------------------------------------------------------- attributes

H5Handle H5File::open_attribute(const std::string& object, const std::string& attr) const {
  const H5Handle o = open_object(object);
  if (H5Aexists(o.get(), attr.c_str()) <= 0) fail(object, "attribute '" + attr + "' not found");
  H5Handle a(H5Aopen(o.get(), attr.c_str(), H5P_DEFAULT), H5Aclose);
  if (!a.valid()) fail(object, "cannot open attribute '" + attr + "'");
  const H5Handle space(H5Aget_space(a.get()), H5Sclose);
  if (H5Sget_simple_extent_npoints(space.get()) != 1) {
    fail(object, "attribute '" + attr + "' is not a single value");
  }
  return a;
}

bool H5File::has_attribute(const std::string& object, const std::string& attr) const {
  if (!exists(object)) return false;
  const H5Handle o = open_object(object);
  return H5Aexists(o.get(), attr.c_str()) > 0;
}

namespace {
struct AttributeType {
  H5T_class_t cls;
  bool is_signed;
};
AttributeType attribute_type(hid_t a) {
  const H5Handle t(H5Aget_type(a), H5Tclose);
  const H5T_class_t cls = H5Tget_class(t.get());
  return {cls, cls == H5T_INTEGER && H5Tget_sign(t.get()) == H5T_SGN_2};
}
}  // namespace

double H5File::attribute_double(const std::string& object, const std::string& attr) const {
  const H5Handle a = open_attribute(object, attr);
  const auto type = attribute_type(a.get());
  if (type.cls != H5T_FLOAT && type.cls != H5T_INTEGER) {
    fail(object, "attribute '" + attr + "': expected a number, found " + class_name(type.cls));
  }
  double v = 0;
  if (H5Aread(a.get(), H5T_NATIVE_DOUBLE, &v) < 0) {
    fail(object, "cannot read attribute '" + attr + "'");
  }
  return v;
}

std::int64_t H5File::attribute_int(const std::string& object, const std::string& attr) const {
  const H5Handle a = open_attribute(object, attr);
  const auto type = attribute_type(a.get());
  if (type.cls != H5T_INTEGER) {
    fail(object, "attribute '" + attr + "': expected an integer, found " + class_name(type.cls));
  }
  std::uint64_t bits = 0;
  if (H5Aread(a.get(), type.is_signed ? H5T_NATIVE_INT64 : H5T_NATIVE_UINT64, &bits) < 0) {
    fail(object, "cannot read attribute '" + attr + "'");
  }
  constexpr auto kMax = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
  if (!type.is_signed && bits > kMax) {
    fail(object, "attribute '" + attr + "' = " + std::to_string(bits) + " exceeds the int64 range");
  }
  return static_cast<std::int64_t>(bits);
}

std::string H5File::attribute_string(const std::string& object, const std::string& attr) const {
  const H5Handle a = open_attribute(object, attr);
  const H5Handle stored(H5Aget_type(a.get()), H5Tclose);
  const std::string where = object + ": attribute '" + attr + "'";
  const H5Handle type = fixed_string_type(stored.get(), where);
  const std::size_t length = H5Tget_size(type.get());
  std::vector<char> bytes(length, '\0');
  if (H5Aread(a.get(), type.get(), bytes.data()) < 0) fail(where, "cannot read");
  return split_fixed(bytes, length, 1).front();
}

std::vector<std::string> H5File::attribute_names(const std::string& object) const {
  const H5Handle o = open_object(object);
  std::vector<std::string> names;
  // No exception may cross HDF5's C frames: a failure stops the iteration.
  const auto collect = [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
    try {
      static_cast<std::vector<std::string>*>(data)->emplace_back(name);
      return 0;
    } catch (...) {
      return -1;
    }
  };
  hsize_t index = 0;
  if (H5Aiterate2(o.get(), H5_INDEX_NAME, H5_ITER_INC, &index, collect, &names) < 0) {
    fail(object, "cannot list attributes");
  }
  return names;
}

}  // namespace cnclab
