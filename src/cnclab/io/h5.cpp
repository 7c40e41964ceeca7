#include "cnclab/io/h5.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>

#include "cnclab/core/error.hpp"
#include "cnclab/core/resources.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// HDF5 settings made before the library is used:
// - H5dont_atexit, once per process (it must precede the library's own
//   initialisation): HDF5 1.10's exit handler closes files still open and
//   segfaults (H5F__close_cb) on a file whose close already failed, e.g.
//   after a disk-full write. cnclab closes every file it completes
//   explicitly, so nothing needs the handler.
// - no automatic error-stack printing, once per thread: in a thread-safe
//   libhdf5 (Debian's is, H5_HAVE_THREADSAFE) the setting lives in each
//   thread's error stack, so one call at start-up would silence only the
//   first thread. cnclab reports errors itself, as IoError.
void init_hdf5() {
  static const bool process_done = [] {
    H5dont_atexit();
    return true;
  }();
  thread_local const bool thread_done = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)process_done;
  (void)thread_done;
}

// The error stack of a failed call is not needed once the failure is an
// IoError. Cleared rather than left for the next call: libhdf5 1.10 leaks the
// entries still on a thread's stack when that thread exits (LeakSanitizer).
void clear_hdf5_errors() {
  H5Eclear2(H5E_DEFAULT);
}

// Strings are stored fixed-length (UTF-8, null-padded), never variable-length:
// variable-length data lives in HDF5's global heap, whose parser in libhdf5
// 1.10 overflows buffers on corrupt files (found by fuzzing the readers), and
// the readers refuse variable-length strings before the library touches it.
H5Handle string_type(std::size_t length, H5T_cset_t cset = H5T_CSET_UTF8) {
  H5Handle t(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(t.get(), std::max<std::size_t>(length, 1));  // size 0 is not a valid type
  H5Tset_strpad(t.get(), H5T_STR_NULLPAD);
  H5Tset_cset(t.get(), cset);
  return t;
}

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

H5Handle link_creation_with_parents() {
  H5Handle p(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(p.get(), 1);
  return p;
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

// Shared by the scalar attribute writers.
template <class WriteFn, class FailFn>
void write_attribute(hid_t object, const std::string& attr, hid_t type, WriteFn&& write,
                     FailFn&& fail) {
  if (H5Aexists(object, attr.c_str()) > 0 && H5Adelete(object, attr.c_str()) < 0) {
    fail("cannot replace attribute '" + attr + "'");
  }
  H5Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  H5Handle a(H5Acreate2(object, attr.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
             H5Aclose);
  if (!a.valid() || write(a.get()) < 0) fail("cannot write attribute '" + attr + "'");
}

}  // namespace

H5Handle& H5Handle::operator=(H5Handle&& other) noexcept {
  if (this != &other) {
    reset();
    id_ = other.id_;
    closer_ = other.closer_;
    other.id_ = -1;
  }
  return *this;
}

void H5Handle::reset() {
  if (id_ >= 0 && closer_) closer_(id_);
  id_ = -1;
}

std::string hdf5_version() {
  init_hdf5();
  unsigned major = 0, minor = 0, release = 0;
  H5get_libversion(&major, &minor, &release);
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(release);
}

// ---------------------------------------------------------------- file

H5File::H5File(fs::path path, H5Handle file) : path_(std::move(path)), file_(std::move(file)) {}

H5File::~H5File() {
  init_hdf5();  // the closing thread may not be the opening one
  file_.reset();
}

void H5File::fail(const std::string& object, const std::string& what) const {
  clear_hdf5_errors();
  throw IoError(path_.string() + ": " + (object.empty() ? "" : object + ": ") + what);
}

H5File H5File::create(const fs::path& path) {
  init_hdf5();
  H5Handle f(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  if (!f.valid()) {
    clear_hdf5_errors();
    throw IoError(path.string() + ": cannot create HDF5 file (missing folder or no permission?)");
  }
  return H5File(path, std::move(f));
}

H5File H5File::open_read(const fs::path& path) {
  init_hdf5();
  std::error_code ec;
  if (!fs::exists(path, ec)) throw IoError(path.string() + ": no such file");
  if (!fs::is_regular_file(path, ec)) throw IoError(path.string() + ": not a regular file");
  if (::access(path.c_str(), R_OK) != 0) {
    throw IoError(path.string() + ": cannot read: " + std::strerror(errno));
  }
  const htri_t is_hdf5 = H5Fis_hdf5(path.c_str());
  clear_hdf5_errors();
  if (is_hdf5 == 0) throw IoError(path.string() + ": not an HDF5 file");
  if (is_hdf5 < 0) throw IoError(path.string() + ": cannot read as HDF5 (truncated or corrupt?)");
  H5Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!f.valid()) {
    clear_hdf5_errors();
    throw IoError(path.string() + ": cannot open HDF5 file (truncated or corrupt?)");
  }
  return H5File(path, std::move(f));
}

void H5File::flush() {
  init_hdf5();
  if (H5Fflush(file_.get(), H5F_SCOPE_GLOBAL) < 0) {
    fail("", "cannot write to disk (disk full or file size limit?)");
  }
}

void H5File::close() {
  if (!file_.valid()) return;
  flush();
  if (H5Fclose(file_.release()) < 0) fail("", "cannot close (write failed?)");
}

// ---------------------------------------------------------------- structure

bool H5File::exists(const std::string& name) const {
  init_hdf5();
  if (name.empty()) return false;
  // Check each prefix: H5Lexists fails, rather than returning false, on a
  // missing intermediate group.
  std::size_t pos = 0;
  while (pos != std::string::npos) {
    pos = name.find('/', pos + 1);
    const std::string prefix = name.substr(0, pos);
    if (prefix.empty() || prefix.back() == '/') continue;  // "/" and doubled or trailing slashes
    const htri_t found = H5Lexists(file_.get(), prefix.c_str(), H5P_DEFAULT);
    if (found < 0) clear_hdf5_errors();  // e.g. a prefix that is a dataset
    if (found <= 0) return false;
  }
  return true;
}

bool H5File::is_group(const std::string& name) const {
  if (!exists(name)) return false;
  const H5Handle o = open_object(name);
  return H5Iget_type(o.get()) == H5I_GROUP;
}

void H5File::create_group(const std::string& name) {
  if (exists(name)) {
    if (!is_group(name)) fail(name, "cannot create group (a dataset has this name)");
    return;
  }
  const H5Handle lcpl = link_creation_with_parents();
  H5Handle g(H5Gcreate2(file_.get(), name.c_str(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!g.valid()) fail(name, "cannot create group");
}

H5Handle H5File::open_object(const std::string& name) const {
  init_hdf5();
  if (!exists(name)) fail(name, "not found");
  H5Handle o(H5Oopen(file_.get(), name.c_str(), H5P_DEFAULT), H5Oclose);
  if (!o.valid()) fail(name, "cannot open object");
  return o;
}

std::vector<std::string> H5File::children(const std::string& group) const {
  if (!exists(group)) fail(group, "cannot list group (not found)");
  const H5Handle o = open_object(group);
  if (H5Iget_type(o.get()) != H5I_GROUP) fail(group, "cannot list group (not a group)");
  H5G_info_t info;
  if (H5Gget_info(o.get(), &info) < 0) fail(group, "cannot list group");
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t len =
        H5Lget_name_by_idx(o.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (len < 0) fail(group, "cannot list group");
    std::string name(static_cast<std::size_t>(len) + 1, '\0');
    if (H5Lget_name_by_idx(o.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(),
                           H5P_DEFAULT) < 0) {
      fail(group, "cannot list group");
    }
    name.resize(static_cast<std::size_t>(len));
    names.push_back(std::move(name));
  }
  return names;
}

// ---------------------------------------------------------------- writing

H5Handle H5File::create_dataset(const std::string& name, hid_t type,
                                const std::vector<hsize_t>& dims) {
  if (exists(name)) fail(name, "cannot create dataset (the name exists)");
  H5Handle space(dims.empty()
                     ? H5Screate(H5S_SCALAR)
                     : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                 H5Sclose);
  if (!space.valid()) fail(name, "cannot create dataspace");
  const H5Handle lcpl = link_creation_with_parents();
  H5Handle d(H5Dcreate2(file_.get(), name.c_str(), type, space.get(), lcpl.get(), H5P_DEFAULT,
                        H5P_DEFAULT),
             H5Dclose);
  if (!d.valid()) fail(name, "cannot create dataset");
  return d;
}

void H5File::write_numeric(const std::string& name, hid_t file_type, hid_t memory_type,
                           const std::vector<hsize_t>& dims, const void* data, bool empty,
                           const std::string& units) {
  H5Handle d = create_dataset(name, file_type, dims);
  if (!empty && H5Dwrite(d.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
    fail(name, "cannot write dataset");
  }
  d.reset();
  if (!units.empty()) set_units(name, units);
}

void H5File::write_vector(const std::string& name, std::span<const double> values,
                          const std::string& units) {
  write_numeric(name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {values.size()}, values.data(),
                values.empty(), units);
}

void H5File::write_int64s(const std::string& name, std::span<const std::int64_t> values,
                          const std::string& units) {
  write_numeric(name, H5T_STD_I64LE, H5T_NATIVE_INT64, {values.size()}, values.data(),
                values.empty(), units);
}

void H5File::write_uint64s(const std::string& name, std::span<const std::uint64_t> values,
                           const std::string& units) {
  write_numeric(name, H5T_STD_U64LE, H5T_NATIVE_UINT64, {values.size()}, values.data(),
                values.empty(), units);
}

void H5File::write_indices(const std::string& name, const std::vector<std::size_t>& values) {
  const std::vector<std::uint64_t> v(values.begin(), values.end());
  write_uint64s(name, v);
}

void H5File::write_matrix(const std::string& name, const Eigen::MatrixXd& m,
                          const std::string& units) {
  write_numeric(name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                {static_cast<hsize_t>(m.cols()), static_cast<hsize_t>(m.rows())}, m.data(),
                m.size() == 0, units);
}

void H5File::write_double(const std::string& name, double value, const std::string& units) {
  write_numeric(name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {}, &value, false, units);
}

void H5File::write_int(const std::string& name, std::int64_t value, const std::string& units) {
  write_numeric(name, H5T_STD_I64LE, H5T_NATIVE_INT64, {}, &value, false, units);
}

void H5File::write_string(const std::string& name, const std::string& text) {
  if (text.find('\0') != std::string::npos) fail(name, "cannot write a string with a NUL byte");
  const H5Handle type = string_type(text.size());
  H5Handle d = create_dataset(name, type.get(), {});
  std::vector<char> bytes(std::max<std::size_t>(text.size(), 1), '\0');
  std::copy(text.begin(), text.end(), bytes.begin());
  if (H5Dwrite(d.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()) < 0) {
    fail(name, "cannot write string");
  }
}

void H5File::write_strings(const std::string& name, const std::vector<std::string>& texts) {
  std::size_t length = 1;
  for (const auto& t : texts) {
    if (t.find('\0') != std::string::npos) fail(name, "cannot write a string with a NUL byte");
    length = std::max(length, t.size());
  }
  const H5Handle type = string_type(length);
  H5Handle d = create_dataset(name, type.get(), {texts.size()});
  std::vector<char> bytes(length * texts.size(), '\0');
  for (std::size_t i = 0; i < texts.size(); ++i) {
    std::copy(texts[i].begin(), texts[i].end(),
              bytes.begin() + static_cast<std::ptrdiff_t>(i * length));
  }
  if (!texts.empty() &&
      H5Dwrite(d.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()) < 0) {
    fail(name, "cannot write strings");
  }
}

void H5File::set_attribute(const std::string& object, const std::string& attr, double value) {
  const H5Handle o = open_object(object);
  write_attribute(
      o.get(), attr, H5T_IEEE_F64LE,
      [&](hid_t a) { return H5Awrite(a, H5T_NATIVE_DOUBLE, &value); },
      [&](const std::string& w) { fail(object, w); });
}

void H5File::set_attribute(const std::string& object, const std::string& attr, std::int64_t value) {
  const H5Handle o = open_object(object);
  write_attribute(
      o.get(), attr, H5T_STD_I64LE, [&](hid_t a) { return H5Awrite(a, H5T_NATIVE_INT64, &value); },
      [&](const std::string& w) { fail(object, w); });
}

void H5File::set_attribute(const std::string& object, const std::string& attr,
                           const std::string& value) {
  if (value.find('\0') != std::string::npos) {
    fail(object, "cannot write attribute '" + attr + "' with a NUL byte");
  }
  const H5Handle o = open_object(object);
  const H5Handle type = string_type(value.size());
  std::vector<char> bytes(std::max<std::size_t>(value.size(), 1), '\0');
  std::copy(value.begin(), value.end(), bytes.begin());
  write_attribute(
      o.get(), attr, type.get(), [&](hid_t a) { return H5Awrite(a, type.get(), bytes.data()); },
      [&](const std::string& w) { fail(object, w); });
}

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
  return string_type(length, cset);
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
