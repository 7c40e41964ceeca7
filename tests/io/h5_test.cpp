#include "cnclab/io/h5.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "cnclab/core/error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

using testing::TempDir;

template <class F>
std::string io_error(F&& f) {
  try {
    f();
  } catch (const IoError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected IoError";
  return "";
}

TEST(H5, RoundTripsEveryType) {
  TempDir dir;
  const auto path = dir / "a.h5";
  Eigen::MatrixXd m(3, 2);  // 3 features x 2 samples
  m << 1, 2, 3, 4, 5, 6;
  {
    H5File f = H5File::create(path);
    f.write_vector("/g/v", std::vector<double>{1.5, -2.25, 1e-300}, "mm");
    f.write_indices("/g/i", {0, 5, 18446744073709551615ull});
    f.write_matrix("/m", m, "µm");
    f.write_string("/s", "line 1\nµm ünïcode");
    f.write_strings("/ss", {"a", "", "µ"});
    f.set_attribute("/", "d", 0.1);
    f.set_attribute("/g", "i", std::int64_t{-7});
    f.set_attribute("/g/v", "s", "text");
  }
  const H5File f = H5File::open_read(path);
  EXPECT_EQ(f.read_vector("/g/v"), (std::vector<double>{1.5, -2.25, 1e-300}));
  EXPECT_EQ(f.attribute_string("/g/v", "units"), "mm");
  EXPECT_EQ(f.read_indices("/g/i"), (std::vector<std::size_t>{0, 5, 18446744073709551615ull}));
  EXPECT_EQ(f.read_matrix("/m"), m);
  EXPECT_EQ(f.attribute_string("/m", "units"), "µm");
  EXPECT_EQ(f.read_string("/s"), "line 1\nµm ünïcode");
  EXPECT_EQ(f.read_strings("/ss"), (std::vector<std::string>{"a", "", "µ"}));
  EXPECT_EQ(f.attribute_double("/", "d"), 0.1);
  EXPECT_EQ(f.attribute_int("/g", "i"), -7);
  EXPECT_EQ(f.attribute_string("/g/v", "s"), "text");
  EXPECT_TRUE(f.exists("/g/v"));
  EXPECT_FALSE(f.exists("/nope/v"));
  EXPECT_EQ(f.children("/g"), (std::vector<std::string>{"i", "v"}));
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
  const hid_t ds = H5Dopen2(file, "/m", H5P_DEFAULT);
  const hid_t space = H5Dget_space(ds);
  hsize_t dims[2];
  ASSERT_EQ(H5Sget_simple_extent_dims(space, dims, nullptr), 2);
  EXPECT_EQ(dims[0], 2u);
  EXPECT_EQ(dims[1], 3u);
  double raw[2][3];
  H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw);
  EXPECT_EQ(raw[0][0], 1);
  EXPECT_EQ(raw[0][2], 3);
  EXPECT_EQ(raw[1][0], 4);
  H5Sclose(space);
  H5Dclose(ds);
  H5Fclose(file);
}

TEST(H5, ErrorsNameFileAndObject) {
  TempDir dir;
  EXPECT_NE(
      io_error([&] { H5File::open_read(dir / "missing.h5"); }).find("missing.h5: no such file"),
      std::string::npos);
  std::ofstream(dir / "text.h5") << "not hdf5 at all";
  EXPECT_NE(io_error([&] { H5File::open_read(dir / "text.h5"); }).find("not an HDF5 file"),
            std::string::npos);
  const auto path = dir / "a.h5";
  {
    H5File f = H5File::create(path);
    f.write_vector("/v", std::vector<double>{1, 2});
    f.write_string("/s", "x");
  }
  const H5File f = H5File::open_read(path);
  EXPECT_NE(io_error([&] { f.read_vector("/nope"); }).find("a.h5: /nope: not found"),
            std::string::npos);
  EXPECT_NE(io_error([&] { f.read_matrix("/v"); }).find("/v: expected rank 2"), std::string::npos);
  EXPECT_NE(io_error([&] { f.read_vector("/s"); }).find("/s: expected floating-point"),
            std::string::npos);
  EXPECT_NE(
      io_error([&] { f.attribute_string("/v", "units"); }).find("attribute 'units' not found"),
      std::string::npos);
}

TEST(H5, TruncatedFileIsAnErrorNotACrash) {
  TempDir dir;
  const auto path = dir / "t.h5";
  {
    H5File f = H5File::create(path);
    f.write_vector("/v", std::vector<double>(10000, 1.0));
  }
  std::filesystem::resize_file(path, std::filesystem::file_size(path) / 2);
  io_error([&] {
    const H5File f = H5File::open_read(path);
    f.read_vector("/v");
  });
}

}  // namespace
}  // namespace cnclab
