#include "cnclab/io/h5.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <thread>

#include "cnclab/core/error.hpp"
#include "common/expect_error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

using testing::TempDir;

// Bytes written to stderr (fd 2) while f runs.
template <class F>
std::string stderr_of(const std::filesystem::path& capture, F&& f) {
  std::fflush(stderr);
  const int saved = ::dup(2);
  const int fd = ::open(capture.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  ::dup2(fd, 2);
  ::close(fd);
  f();
  std::fflush(stderr);
  ::dup2(saved, 2);
  ::close(saved);
  std::ifstream in(capture);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(H5, RoundTripsEveryType) {
  TempDir dir;
  const auto path = dir / "a.h5";
  Eigen::MatrixXd m(3, 2);  // 3 features x 2 samples
  m << 1, 2, 3, 4, 5, 6;
  const std::vector<double> doubles{1.5, -2.25, 1e-300, std::numeric_limits<double>::max()};
  const std::vector<std::int64_t> ints{0, -1, std::numeric_limits<std::int64_t>::min(),
                                       std::numeric_limits<std::int64_t>::max()};
  const std::vector<std::uint64_t> uints{0, 1, std::numeric_limits<std::uint64_t>::max()};
  {
    H5File f = H5File::create(path);
    f.write_vector("/g/v", doubles, "mm");
    f.write_int64s("/g/i64", ints, "1");
    f.write_uint64s("/g/u64", uints);
    f.write_indices("/g/i", {0, 5, 18446744073709551615ull});
    f.write_matrix("/m", m, "µm");
    f.write_matrix("/empty", Eigen::MatrixXd(3, 0), "mm");
    f.write_vector("/none", std::vector<double>{});
    f.write_double("/s/x", -0.1, "s");
    f.write_int("/s/n", -42);
    f.write_string("/text", "line 1\nµm ünïcode");
    f.write_string("/blank", "");
    f.write_strings("/ss", {"a", "", "µ"});
    f.create_group("/grp/sub");
    f.set_attribute("/", "d", 0.1);
    f.set_attribute("/g", "i", std::int64_t{-7});
    f.set_attribute("/g/v", "s", "text");
    f.set_attribute("/g/v", "s", "replaced");
    f.set_units("/g/u64", "count");
    f.close();
  }
  const H5File f = H5File::open_read(path);
  EXPECT_EQ(f.read_vector("/g/v"), doubles);
  EXPECT_EQ(f.units("/g/v"), "mm");
  EXPECT_EQ(f.read_int64s("/g/i64"), ints);
  EXPECT_EQ(f.units("/g/i64"), "1");
  EXPECT_EQ(f.read_uint64s("/g/u64"), uints);
  EXPECT_EQ(f.units("/g/u64"), "count");
  EXPECT_EQ(f.read_indices("/g/i"), (std::vector<std::size_t>{0, 5, 18446744073709551615ull}));
  EXPECT_EQ(f.read_matrix("/m"), m);
  EXPECT_EQ(f.units("/m"), "µm");
  const Eigen::MatrixXd empty = f.read_matrix("/empty");
  EXPECT_EQ(empty.rows(), 3);
  EXPECT_EQ(empty.cols(), 0);
  EXPECT_TRUE(f.read_vector("/none").empty());
  EXPECT_EQ(f.read_double("/s/x"), -0.1);
  EXPECT_EQ(f.units("/s/x"), "s");
  EXPECT_EQ(f.read_int("/s/n"), -42);
  EXPECT_EQ(f.read_string("/text"), "line 1\nµm ünïcode");
  EXPECT_EQ(f.read_string("/blank"), "");
  EXPECT_EQ(f.read_strings("/ss"), (std::vector<std::string>{"a", "", "µ"}));
  EXPECT_EQ(f.attribute_double("/", "d"), 0.1);
  EXPECT_EQ(f.attribute_int("/g", "i"), -7);
  EXPECT_EQ(f.attribute_double("/g", "i"), -7.0);
  EXPECT_EQ(f.attribute_string("/g/v", "s"), "replaced");
  EXPECT_TRUE(f.exists("/g/v"));
  EXPECT_TRUE(f.exists("/"));
  EXPECT_FALSE(f.exists(""));
  EXPECT_FALSE(f.exists("/nope/v"));
  EXPECT_FALSE(f.exists("/g/v/below_a_dataset"));
  EXPECT_TRUE(f.is_group("/grp/sub"));
  EXPECT_FALSE(f.is_group("/g/v"));
  EXPECT_TRUE(f.has_attribute("/g/v", "units"));
  EXPECT_FALSE(f.has_attribute("/g/v", "nope"));
  EXPECT_FALSE(f.has_attribute("/nope", "units"));
  EXPECT_EQ(f.children("/g"), (std::vector<std::string>{"i", "i64", "u64", "v"}));
  EXPECT_EQ(f.children("/"), (std::vector<std::string>{"blank", "empty", "g", "grp", "m", "none",
                                                       "s", "ss", "text"}));
  EXPECT_EQ(f.attribute_names("/g/v"), (std::vector<std::string>{"s", "units"}));
}

// The matrix convention checked through the raw C API: an Eigen matrix of
// 3 features x 2 samples is a (2, 3) dataset whose row j is sample j.
TEST(H5, MatrixIsStoredSamplesByFeaturesInCOrder) {
  TempDir dir;
  const auto path = dir / "m.h5";
  Eigen::MatrixXd m(3, 2);
  m << 1, 4, 2, 5, 3, 6;  // sample 0 = (1,2,3), sample 1 = (4,5,6)
  H5File::create(path).write_matrix("/m", m);
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t ds = H5Dopen2(file, "/m", H5P_DEFAULT);
  const hid_t space = H5Dget_space(ds);
  hsize_t dims[2];
  ASSERT_EQ(H5Sget_simple_extent_dims(space, dims, nullptr), 2);
  EXPECT_EQ(dims[0], 2u);
  EXPECT_EQ(dims[1], 3u);
  double raw[2][3];
  ASSERT_GE(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw), 0);
  EXPECT_EQ(raw[0][0], 1);
  EXPECT_EQ(raw[0][1], 2);
  EXPECT_EQ(raw[0][2], 3);
  EXPECT_EQ(raw[1][0], 4);
  EXPECT_EQ(raw[1][2], 6);
  H5Sclose(space);
  H5Dclose(ds);
  H5Fclose(file);
}

TEST(H5, MissingUnreadableOrNonHdf5FilesAreErrorsNamingThem) {
  TempDir dir;
  EXPECT_IO_ERROR(H5File::open_read(dir / "missing.h5"), "missing.h5: no such file");
  EXPECT_IO_ERROR(H5File::open_read(dir.path()), "not a regular file");
  std::ofstream(dir / "text.h5") << "not hdf5 at all, just some text bytes\n";
  EXPECT_IO_ERROR(H5File::open_read(dir / "text.h5"), "text.h5: not an HDF5 file");
  std::ofstream(dir / "empty.h5").close();
  EXPECT_IO_ERROR(H5File::open_read(dir / "empty.h5"), "empty.h5: ");
  EXPECT_IO_ERROR(H5File::create(dir / "no/such/folder/x.h5"), "x.h5: cannot create HDF5 file");
}

TEST(H5, TruncatedFileIsAnErrorNamingItNotACrash) {
  TempDir dir;
  const auto path = dir / "t.h5";
  {
    H5File f = H5File::create(path);
    f.write_vector("/v", std::vector<double>(10000, 1.0));
    f.set_attribute("/", "a", 1.0);
  }
  std::filesystem::resize_file(path, std::filesystem::file_size(path) / 2);
  EXPECT_IO_ERROR(
      {
        const H5File f = H5File::open_read(path);
        f.read_vector("/v");
      },
      path.string());
}

TEST(H5, WrongObjectsAreErrorsNamingFileAndObject) {
  TempDir dir;
  const auto path = dir / "a.h5";
  {
    H5File f = H5File::create(path);
    f.write_vector("/v", std::vector<double>{1, 2});
    f.write_int64s("/neg", std::vector<std::int64_t>{3, -1});
    f.write_uint64s("/big", std::vector<std::uint64_t>{1ull << 63});
    f.write_string("/s", "x");
    f.write_double("/x", 1.0);
    f.create_group("/grp");
    f.set_attribute("/v", "text", "abc");
    EXPECT_IO_ERROR(f.write_vector("/v", std::vector<double>{3}), "a.h5: /v: cannot create");
    EXPECT_IO_ERROR(f.create_group("/v"), "/v: cannot create group");
    EXPECT_IO_ERROR(f.set_attribute("/nope", "a", 1.0), "a.h5: /nope: not found");
    EXPECT_IO_ERROR(f.write_string("/nul", std::string("a\0b", 3)), "NUL");
  }
  const H5File f = H5File::open_read(path);
  EXPECT_IO_ERROR(f.read_vector("/nope"), "a.h5: /nope: cannot read dataset (not found)");
  EXPECT_IO_ERROR(f.read_vector("/grp"), "a.h5: /grp: cannot read dataset (not a dataset)");
  EXPECT_IO_ERROR(f.read_matrix("/v"), "a.h5: /v: expected rank 2, found shape (2)");
  EXPECT_IO_ERROR(f.read_double("/v"), "/v: expected a scalar, found shape (2)");
  EXPECT_IO_ERROR(f.read_vector("/x"), "/x: expected rank 1, found a scalar");
  EXPECT_IO_ERROR(f.read_vector("/s"), "/s: expected floating-point values, found a string");
  EXPECT_IO_ERROR(f.read_int64s("/v"), "/v: expected integer values, found floating-point");
  EXPECT_IO_ERROR(f.read_string("/v"), "/v: expected a string");
  EXPECT_IO_ERROR(f.read_strings("/s"), "/s: expected rank 1, found a scalar");
  EXPECT_IO_ERROR(f.read_indices("/neg"), "/neg: negative value -1 at index 1");
  EXPECT_IO_ERROR(f.read_int64s("/big"), "/big: value 9223372036854775808 at index 0 exceeds");
  EXPECT_IO_ERROR(f.children("/v"), "/v: cannot list group (not a group)");
  EXPECT_IO_ERROR(f.units("/v"), "a.h5: /v: attribute 'units' not found");
  EXPECT_IO_ERROR(f.attribute_double("/v", "text"), "attribute 'text': expected a number");
  EXPECT_IO_ERROR(f.attribute_int("/", "x"), "attribute 'x' not found");
}

// Objects cnclab never writes, made with the raw C API: the readers refuse
// them with an IoError instead of misreading or allocating for them.
TEST(H5, ForeignObjectsAreRefused) {
  TempDir dir;
  const auto path = dir / "foreign.h5";
  {
    const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    // 3-D float dataset.
    const hsize_t d3[3] = {2, 2, 2};
    hid_t space = H5Screate_simple(3, d3, nullptr);
    hid_t ds =
        H5Dcreate2(file, "/cube", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dclose(ds);
    H5Sclose(space);
    // Variable-length string.
    const hid_t vlen = H5Tcopy(H5T_C_S1);
    H5Tset_size(vlen, H5T_VARIABLE);
    space = H5Screate(H5S_SCALAR);
    ds = H5Dcreate2(file, "/vlen", vlen, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const char* text = "hello";
    H5Dwrite(ds, vlen, H5S_ALL, H5S_ALL, H5P_DEFAULT, &text);
    H5Dclose(ds);
    H5Sclose(space);
    H5Tclose(vlen);
    // 2^40 doubles (8 TiB) declared, chunked, never written: no bytes stored.
    const hsize_t huge[1] = {hsize_t{1} << 40}, chunk[1] = {1024};
    space = H5Screate_simple(1, huge, nullptr);
    const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, 1, chunk);
    ds = H5Dcreate2(file, "/huge", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    H5Dclose(ds);
    H5Pclose(dcpl);
    H5Sclose(space);
    // Null dataspace.
    space = H5Screate(H5S_NULL);
    ds = H5Dcreate2(file, "/null", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dclose(ds);
    H5Sclose(space);
    H5Fclose(file);
  }
  const H5File f = H5File::open_read(path);
  EXPECT_IO_ERROR(f.read_matrix("/cube"),
                  "foreign.h5: /cube: expected rank 2, found shape (2, 2, 2)");
  EXPECT_IO_ERROR(f.read_string("/vlen"),
                  "foreign.h5: /vlen: variable-length strings are not read");
  EXPECT_IO_ERROR(f.read_vector("/huge"), "foreign.h5: /huge: declares 8.0 TiB of data but stores");
  EXPECT_IO_ERROR(f.read_double("/null"), "/null: expected a scalar, found no data");
}

// Other writers' types within the same class are converted: ASCII strings
// (h5py's fixed-length default), space padding, int32, float32.
TEST(H5, OtherWritersTypesAreRead) {
  TempDir dir;
  const auto path = dir / "h5py.h5";
  {
    const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    const hid_t scalar = H5Screate(H5S_SCALAR);
    const hid_t ascii = H5Tcopy(H5T_C_S1);  // ASCII, null-terminated
    H5Tset_size(ascii, 6);
    hid_t ds = H5Dcreate2(file, "/ascii", ascii, scalar, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(ds, ascii, H5S_ALL, H5S_ALL, H5P_DEFAULT, "abc\0\0");
    H5Dclose(ds);
    const hid_t spaced = H5Tcopy(H5T_FORTRAN_S1);  // space-padded
    H5Tset_size(spaced, 6);
    ds = H5Dcreate2(file, "/spaced", spaced, scalar, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(ds, spaced, H5S_ALL, H5S_ALL, H5P_DEFAULT, "abc   ");
    H5Dclose(ds);
    const hsize_t n = 3;
    const hid_t space = H5Screate_simple(1, &n, nullptr);
    const std::int32_t i32[3] = {-5, 0, 7};
    ds = H5Dcreate2(file, "/i32", H5T_STD_I32BE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(ds, H5T_NATIVE_INT32, H5S_ALL, H5S_ALL, H5P_DEFAULT, i32);
    H5Dclose(ds);
    const float f32[3] = {0.5f, -1.25f, 3.0f};
    ds = H5Dcreate2(file, "/f32", H5T_IEEE_F32LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(ds, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, f32);
    H5Dclose(ds);
    H5Sclose(space);
    H5Tclose(spaced);
    H5Tclose(ascii);
    H5Sclose(scalar);
    H5Fclose(file);
  }
  const H5File f = H5File::open_read(path);
  EXPECT_EQ(f.read_string("/ascii"), "abc");
  EXPECT_EQ(f.read_string("/spaced"), "abc");
  EXPECT_EQ(f.read_int64s("/i32"), (std::vector<std::int64_t>{-5, 0, 7}));
  EXPECT_EQ(f.read_vector("/f32"), (std::vector<double>{0.5, -1.25, 3.0}));
  EXPECT_IO_ERROR(f.read_indices("/i32"), "/i32: negative value -5 at index 0");
}

// HDF5 prints its error stack to stderr unless turned off, and in the
// thread-safe library that setting is per thread. A failing call on a fresh
// thread must print nothing; the raw call beside it shows it would.
TEST(H5, ErrorStackIsNotPrintedOnAnyThread) {
  TempDir dir;
  const auto missing = dir / "no/such/folder/x.h5";
  const std::string raw = stderr_of(dir / "raw.txt", [&] {
    std::thread([&] {
      const hid_t f = H5Fcreate(missing.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
      EXPECT_LT(f, 0);
      H5Eclear2(H5E_DEFAULT);  // libhdf5 leaks a thread's uncleared error stack at exit
    }).join();
  });
  EXPECT_NE(raw.find("HDF5"), std::string::npos) << "control: libhdf5 printed nothing";
  const std::string wrapped = stderr_of(dir / "wrapped.txt", [&] {
    std::thread([&] { EXPECT_IO_ERROR(H5File::create(missing), "cannot create"); }).join();
  });
  EXPECT_EQ(wrapped, "");
}

TEST(H5, FileIsMovable) {
  TempDir dir;
  H5File a = H5File::create(dir / "m.h5");
  H5File b = std::move(a);
  b.write_double("/x", 2.0);
  b.close();
  EXPECT_EQ(H5File::open_read(dir / "m.h5").read_double("/x"), 2.0);
}

}  // namespace
}  // namespace cnclab
