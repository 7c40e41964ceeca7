// H5File: file, structure and writing (datasets, attributes); reading is in
// h5_read.cpp.
#include "cnclab/io/h5.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "cnclab/core/error.hpp"
#include "cnclab/io/h5_detail.hpp"

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

H5Handle link_creation_with_parents() {
  H5Handle p(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(p.get(), 1);
  return p;
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

namespace h5_detail {

// Strings are stored fixed-length (UTF-8, null-padded), never variable-length:
// variable-length data lives in HDF5's global heap, whose parser in libhdf5
// 1.10 overflows buffers on corrupt files (found by fuzzing the readers), and
// the readers refuse variable-length strings before the library touches it.
H5Handle string_type(std::size_t length, H5T_cset_t cset) {
  H5Handle t(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(t.get(), std::max<std::size_t>(length, 1));  // size 0 is not a valid type
  H5Tset_strpad(t.get(), H5T_STR_NULLPAD);
  H5Tset_cset(t.get(), cset);
  return t;
}

}  // namespace h5_detail

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
  const H5Handle type = h5_detail::string_type(text.size());
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
  const H5Handle type = h5_detail::string_type(length);
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
  const H5Handle type = h5_detail::string_type(value.size());
  std::vector<char> bytes(std::max<std::size_t>(value.size(), 1), '\0');
  std::copy(value.begin(), value.end(), bytes.begin());
  write_attribute(
      o.get(), attr, type.get(), [&](hid_t a) { return H5Awrite(a, type.get(), bytes.data()); },
      [&](const std::string& w) { fail(object, w); });
}

}  // namespace cnclab
