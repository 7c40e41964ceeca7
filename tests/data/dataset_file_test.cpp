#include "cnclab/data/dataset_file.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>

#include "cnclab/core/error.hpp"
#include "cnclab/data/friedman1.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

using testing::TempDir;

Dataset small() {
  Rng rng(1);
  return generate_friedman1({20, 6, 0.5}, rng);
}

TEST(DatasetFile, RoundTripKeepsEverythingAndTheHash) {
  TempDir dir;
  const Dataset d = small();
  write_dataset(dir / "d.h5", d);
  const Dataset r = read_dataset(dir / "d.h5");
  EXPECT_EQ(r.inputs, d.inputs);
  EXPECT_EQ(r.targets, d.targets);
  EXPECT_EQ(r.input_names, d.input_names);
  EXPECT_EQ(r.target_units, d.target_units);
  EXPECT_EQ(r.generator_config, d.generator_config);
  EXPECT_EQ(r.content_hash(), d.content_hash());
}

// Reads the file through the raw HDF5 C API, not the wrapper classes.
TEST(DatasetFile, ReadableByPlainHdf5CApi) {
  TempDir dir;
  const Dataset d = small();
  write_dataset(dir / "d.h5", d);
  const hid_t file = H5Fopen((dir / "d.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t ds = H5Dopen2(file, "/inputs", H5P_DEFAULT);
  const hid_t space = H5Dget_space(ds);
  hsize_t dims[2] = {0, 0};
  H5Sget_simple_extent_dims(space, dims, nullptr);
  EXPECT_EQ(dims[0], 20u);  // samples
  EXPECT_EQ(dims[1], 6u);   // features
  std::vector<double> raw(20 * 6);
  H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data());
  EXPECT_EQ(raw[3 * 6 + 2], d.inputs(2, 3));  // sample 3, feature x3
  const hid_t attr = H5Aopen(ds, "units", H5P_DEFAULT);
  ASSERT_GE(attr, 0);
  const hid_t type = H5Aget_type(attr);
  ASSERT_EQ(H5Tget_class(type), H5T_STRING);
  ASSERT_EQ(H5Tis_variable_str(type), 0);  // fixed-length by design
  std::string units(H5Tget_size(type), '\0');
  H5Aread(attr, type, units.data());
  EXPECT_EQ(units.substr(0, units.find('\0')), "1");
  H5Tclose(type);
  H5Aclose(attr);
  H5Sclose(space);
  H5Dclose(ds);
  H5Fclose(file);
}

TEST(DatasetFile, TamperedValueIsDetectedByHash) {
  TempDir dir;
  write_dataset(dir / "d.h5", small());
  {
    const hid_t file = H5Fopen((dir / "d.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t ds = H5Dopen2(file, "/targets", H5P_DEFAULT);
    std::vector<double> t(20);
    H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, t.data());
    t[7] += 1e-9;
    H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, t.data());
    H5Dclose(ds);
    H5Fclose(file);
  }
  try {
    read_dataset(dir / "d.h5");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("content hash mismatch"), std::string::npos);
  }
}

TEST(Dataset, ValidateNamesNonFiniteFeatureAndSample) {
  Dataset d = small();
  d.inputs(4, 11) = std::nan("");
  try {
    d.validate();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("x5 of sample 11"), std::string::npos) << e.what();
  }
}

TEST(Dataset, HashChangesWithOneValue) {
  Dataset d = small();
  const auto h = d.content_hash();
  d.targets(0, 0) = std::nextafter(d.targets(0, 0), 1e9);
  EXPECT_NE(d.content_hash(), h);
}

}  // namespace
}  // namespace cnclab
