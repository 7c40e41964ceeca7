#include "cnclab/io/h5.hpp"

#include <algorithm>
#include <cstring>
#include <functional>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// Process-wide HDF5 settings, made once before the library's first use:
// - H5dont_atexit: HDF5 1.10's exit handler closes files still open and
//   segfaults (H5F__close_cb) on a file whose close already failed, e.g.
//   after a disk-full write. cnclab closes every file it completes explicitly,
//   so nothing needs the handler.
// - no automatic error-stack printing: cnclab reports errors itself.
void init_hdf5() {
  static const bool done = [] {
    H5dont_atexit();
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)done;
}

// Strings are stored fixed-length (UTF-8, null-padded), never variable-length:
// variable-length data lives in HDF5's global heap, whose parser in libhdf5
// 1.10 overflows buffers on corrupt files (found by fuzzing the readers), and
// the readers refuse variable-length strings before the library touches it.
H5Handle string_type(std::size_t length) {
  H5Handle t(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(t.get(), std::max<std::size_t>(length, 1));  // size 0 is not a valid type
  H5Tset_strpad(t.get(), H5T_STR_NULLPAD);
  H5Tset_cset(t.get(), H5T_CSET_UTF8);
  return t;
}

// Bytes of `count` fixed-length strings of `length` into std::strings, each
// cut at its first NUL (null-padded or null-terminated).
std::vector<std::string> split_fixed(const std::vector<char>& bytes, std::size_t length,
                                     std::size_t count) {
  std::vector<std::string> out;
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

H5File::H5File(fs::path path, H5Handle file) : path_(std::move(path)), file_(std::move(file)) {}

void H5File::fail(const std::string& object, const std::string& what) const {
  throw IoError(path_.string() + ": " + (object.empty() ? "" : object + ": ") + what);
}

H5File H5File::create(const fs::path& path) {
  init_hdf5();
  H5Handle f(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  if (!f.valid()) throw IoError(path.string() + ": cannot create HDF5 file");
  return H5File(path, std::move(f));
}

H5File H5File::open_read(const fs::path& path) {
  init_hdf5();
  std::error_code ec;
  if (!fs::exists(path, ec)) throw IoError(path.string() + ": no such file");
  if (!fs::is_regular_file(path, ec)) throw IoError(path.string() + ": not a regular file");
  if (H5Fis_hdf5(path.c_str()) <= 0) {
    throw IoError(path.string() + ": not an HDF5 file (or truncated/corrupt)");
  }
  H5Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!f.valid()) throw IoError(path.string() + ": cannot open HDF5 file (truncated or corrupt?)");
  return H5File(path, std::move(f));
}

void H5File::flush() {
  if (H5Fflush(file_.get(), H5F_SCOPE_GLOBAL) < 0) {
    fail("", "cannot write to disk (disk full or file size limit?)");
  }
}

void H5File::close() {
  if (!file_.valid()) return;
  flush();
  file_.reset();
}

bool H5File::exists(const std::string& name) const {
  // Check each prefix: H5Lexists fails on a missing intermediate group.
  std::size_t pos = 0;
  while (pos != std::string::npos) {
    pos = name.find('/', pos + 1);
    const std::string prefix = name.substr(0, pos);
    if (prefix.empty() || prefix == "/") continue;
    if (H5Lexists(file_.get(), prefix.c_str(), H5P_DEFAULT) <= 0) return false;
  }
  return true;
}

void H5File::create_group(const std::string& name) {
  if (exists(name)) return;
  const H5Handle lcpl = link_creation_with_parents();
  H5Handle g(H5Gcreate2(file_.get(), name.c_str(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!g.valid()) fail(name, "cannot create group");
}

H5Handle H5File::create_dataset(const std::string& name, hid_t type,
                                const std::vector<hsize_t>& dims) {
  H5Handle space(dims.empty()
                     ? H5Screate(H5S_SCALAR)
                     : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                 H5Sclose);
  const H5Handle lcpl = link_creation_with_parents();
  H5Handle d(H5Dcreate2(file_.get(), name.c_str(), type, space.get(), lcpl.get(), H5P_DEFAULT,
                        H5P_DEFAULT),
             H5Dclose);
  if (!d.valid()) fail(name, "cannot create dataset");
  return d;
}

void H5File::write_vector(const std::string& name, std::span<const double> values,
                          const std::string& units) {
  H5Handle d = create_dataset(name, H5T_IEEE_F64LE, {values.size()});
  if (!values.empty() &&
      H5Dwrite(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0) {
    fail(name, "cannot write dataset");
  }
  d.reset();
  if (!units.empty()) set_attribute(name, "units", units);
}

void H5File::write_indices(const std::string& name, const std::vector<std::size_t>& values) {
  std::vector<std::uint64_t> v(values.begin(), values.end());
  H5Handle d = create_dataset(name, H5T_STD_U64LE, {v.size()});
  if (!v.empty() &&
      H5Dwrite(d.get(), H5T_NATIVE_UINT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0) {
    fail(name, "cannot write dataset");
  }
}

void H5File::write_matrix(const std::string& name, const Eigen::MatrixXd& m,
                          const std::string& units) {
  H5Handle d = create_dataset(name, H5T_IEEE_F64LE,
                              {static_cast<hsize_t>(m.cols()), static_cast<hsize_t>(m.rows())});
  if (m.size() > 0 &&
      H5Dwrite(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, m.data()) < 0) {
    fail(name, "cannot write dataset");
  }
  d.reset();
  if (!units.empty()) set_attribute(name, "units", units);
}

void H5File::write_string(const std::string& name, const std::string& text) {
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
  for (const auto& t : texts) length = std::max(length, t.size());
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

H5Handle H5File::open_object(const std::string& name) const {
  if (name != "/" && !exists(name)) fail(name, "not found");
  H5Handle o(H5Oopen(file_.get(), name.c_str(), H5P_DEFAULT), H5Oclose);
  if (!o.valid()) fail(name, "cannot open object");
  return o;
}

namespace {
template <class WriteFn>
void write_attribute(hid_t object, const std::string& attr, hid_t type, WriteFn&& write,
                     const std::function<void(const std::string&)>& fail) {
  if (H5Aexists(object, attr.c_str()) > 0) H5Adelete(object, attr.c_str());
  H5Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  H5Handle a(H5Acreate2(object, attr.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
             H5Aclose);
  if (!a.valid() || write(a.get()) < 0) fail("cannot write attribute '" + attr + "'");
}
}  // namespace

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
  const H5Handle o = open_object(object);
  const H5Handle type = string_type(value.size());
  std::vector<char> bytes(std::max<std::size_t>(value.size(), 1), '\0');
  std::copy(value.begin(), value.end(), bytes.begin());
  write_attribute(
      o.get(), attr, type.get(), [&](hid_t a) { return H5Awrite(a, type.get(), bytes.data()); },
      [&](const std::string& w) { fail(object, w); });
}

H5Handle H5File::open_dataset(const std::string& name) const {
  if (!exists(name)) fail(name, "not found");
  H5Handle d(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!d.valid()) fail(name, "cannot open dataset");
  return d;
}

std::vector<hsize_t> H5File::dims(hid_t dataset, const std::string& name, int rank) const {
  H5Handle space(H5Dget_space(dataset), H5Sclose);
  const int actual = H5Sget_simple_extent_ndims(space.get());
  if (actual != rank) {
    fail(name, "expected rank " + std::to_string(rank) + ", found " + std::to_string(actual));
  }
  std::vector<hsize_t> d(static_cast<std::size_t>(rank));
  if (rank > 0) H5Sget_simple_extent_dims(space.get(), d.data(), nullptr);
  return d;
}

namespace {
H5T_class_t type_class(hid_t dataset) {
  H5Handle t(H5Dget_type(dataset), H5Tclose);
  return H5Tget_class(t.get());
}
}  // namespace

std::vector<double> H5File::read_vector(const std::string& name) const {
  const H5Handle d = open_dataset(name);
  if (type_class(d.get()) != H5T_FLOAT) fail(name, "expected floating-point values");
  const auto n = dims(d.get(), name, 1)[0];
  std::vector<double> out(n);
  if (n && H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
    fail(name, "cannot read dataset");
  }
  return out;
}

std::vector<std::size_t> H5File::read_indices(const std::string& name) const {
  const H5Handle d = open_dataset(name);
  if (type_class(d.get()) != H5T_INTEGER) fail(name, "expected integer values");
  const auto n = dims(d.get(), name, 1)[0];
  std::vector<std::uint64_t> v(n);
  if (n && H5Dread(d.get(), H5T_NATIVE_UINT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0) {
    fail(name, "cannot read dataset");
  }
  return {v.begin(), v.end()};
}

Eigen::MatrixXd H5File::read_matrix(const std::string& name) const {
  const H5Handle d = open_dataset(name);
  if (type_class(d.get()) != H5T_FLOAT) fail(name, "expected floating-point values");
  const auto shape = dims(d.get(), name, 2);
  Eigen::MatrixXd m(static_cast<Eigen::Index>(shape[1]), static_cast<Eigen::Index>(shape[0]));
  if (m.size() &&
      H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, m.data()) < 0) {
    fail(name, "cannot read dataset");
  }
  return m;
}

H5Handle H5File::fixed_string_type(hid_t stored, const std::string& object) const {
  if (H5Tget_class(stored) != H5T_STRING) fail(object, "expected a string");
  if (H5Tis_variable_str(stored) != 0) {
    fail(object, "variable-length strings are not read (cnclab writes fixed-length strings)");
  }
  const std::size_t length = H5Tget_size(stored);
  if (length == 0 || length > kMaxStringBytes) fail(object, "string length out of range");
  return string_type(length);
}

std::string H5File::read_string(const std::string& name) const {
  const H5Handle d = open_dataset(name);
  dims(d.get(), name, 0);
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
  const H5Handle d = open_dataset(name);
  const auto n = dims(d.get(), name, 1)[0];
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

H5Handle H5File::open_attribute(const std::string& object, const std::string& attr) const {
  const H5Handle o = open_object(object);
  if (H5Aexists(o.get(), attr.c_str()) <= 0) fail(object, "attribute '" + attr + "' not found");
  H5Handle a(H5Aopen(o.get(), attr.c_str(), H5P_DEFAULT), H5Aclose);
  if (!a.valid()) fail(object, "cannot open attribute '" + attr + "'");
  H5Handle space(H5Aget_space(a.get()), H5Sclose);
  if (H5Sget_simple_extent_npoints(space.get()) != 1) {
    fail(object, "attribute '" + attr + "' is not a single value");
  }
  return a;
}

bool H5File::has_attribute(const std::string& object, const std::string& attr) const {
  if (object != "/" && !exists(object)) return false;
  const H5Handle o = open_object(object);
  return H5Aexists(o.get(), attr.c_str()) > 0;
}

namespace {
H5T_class_t attribute_class(hid_t a) {
  H5Handle t(H5Aget_type(a), H5Tclose);
  return H5Tget_class(t.get());
}
}  // namespace

double H5File::attribute_double(const std::string& object, const std::string& attr) const {
  const H5Handle a = open_attribute(object, attr);
  const auto cls = attribute_class(a.get());
  if (cls != H5T_FLOAT && cls != H5T_INTEGER)
    fail(object, "attribute '" + attr + "' is not a number");
  double v = 0;
  if (H5Aread(a.get(), H5T_NATIVE_DOUBLE, &v) < 0)
    fail(object, "cannot read attribute '" + attr + "'");
  return v;
}

std::int64_t H5File::attribute_int(const std::string& object, const std::string& attr) const {
  const H5Handle a = open_attribute(object, attr);
  if (attribute_class(a.get()) != H5T_INTEGER) {
    fail(object, "attribute '" + attr + "' is not an integer");
  }
  std::int64_t v = 0;
  if (H5Aread(a.get(), H5T_NATIVE_INT64, &v) < 0)
    fail(object, "cannot read attribute '" + attr + "'");
  return v;
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
  const auto collect = [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->emplace_back(name);
    return 0;
  };
  hsize_t index = 0;
  if (H5Aiterate2(o.get(), H5_INDEX_NAME, H5_ITER_INC, &index, collect, &names) < 0) {
    fail(object, "cannot list attributes");
  }
  return names;
}

std::vector<std::string> H5File::children(const std::string& group) const {
  const H5Handle g(H5Gopen2(file_.get(), group.c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.valid()) fail(group, "not a group");
  H5G_info_t info;
  if (H5Gget_info(g.get(), &info) < 0) fail(group, "cannot list group");
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t len =
        H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (len < 0) fail(group, "cannot list group");
    std::string name(static_cast<std::size_t>(len) + 1, '\0');
    H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(),
                       H5P_DEFAULT);
    name.resize(static_cast<std::size_t>(len));
    names.push_back(name);
  }
  return names;
}

}  // namespace cnclab
