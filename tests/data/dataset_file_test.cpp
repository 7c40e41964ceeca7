#include "cnclab/data/dataset_file.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "cnclab/core/error.hpp"
#include "cnclab/data/friedman1.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "common/expect_error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

using testing::TempDir;
namespace fs = std::filesystem;

constexpr Eigen::Index kSamples = 20;
constexpr Eigen::Index kInputs = 6;

Dataset small() {
  Rng rng(1);
  return generate_friedman1({kSamples, kInputs, 0.5}, rng);
}

// A hand-made dataset with mixed units and non-ASCII text.
Dataset mixed() {
  Dataset d;
  d.inputs.resize(2, 3);
  d.inputs << 1, 2, 3, 4, 5, 6;
  d.targets.resize(2, 3);
  d.targets << 0.5, -0.5, 1e-6, 7, 8, 9;
  d.input_names = {"x", "angle"};
  d.input_units = {"mm", "deg"};
  d.target_names = {"step error", "t"};
  d.target_units = {"µm", "µm"};
  d.generator = "hand";
  d.generator_config = "note: \"µ\"\n";
  return d;
}

// mixed() with two metadata columns (not inputs).
Dataset with_metadata() {
  Dataset d = mixed();
  d.metadata.resize(2, 3);
  d.metadata << 0, 1, 2, 0.25, 0.5, 1;
  d.metadata_names = {"line", "u_i"};
  d.metadata_units = {"1", "1"};
  return d;
}

// Runs `edit` on the file opened read-write through the raw C API.
template <class F>
void edit_raw(const fs::path& path, F&& edit) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  edit(file);
  H5Fclose(file);
}

// Replaces element `index` (row-major) of the float64 dataset `name` of
// `size` elements by change(element), through the raw C API.
template <class F>
void edit_value(const fs::path& path, const char* name, std::size_t size, std::size_t index,
                F&& change) {
  edit_raw(path, [&](hid_t file) {
    const hid_t ds = H5Dopen2(file, name, H5P_DEFAULT);
    std::vector<double> v(size);
    H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    v[index] = change(v[index]);
    H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    H5Dclose(ds);
  });
}

std::string raw_string_attribute(hid_t object, const char* name) {
  const hid_t attr = H5Aopen(object, name, H5P_DEFAULT);
  if (attr < 0) return "<missing>";
  const hid_t type = H5Aget_type(attr);
  std::string s(H5Tget_size(type), '\0');
  H5Aread(attr, type, s.data());
  H5Tclose(type);
  H5Aclose(attr);
  return s.substr(0, s.find('\0'));
}

TEST(DatasetFile, RoundTripKeepsEverythingAndTheHash) {
  TempDir dir;
  for (const Dataset& d : {small(), mixed()}) {
    const auto path = dir / (d.generator + ".h5");
    write_dataset(path, d);
    const Dataset r = read_dataset(path);
    EXPECT_EQ(r.inputs, d.inputs);
    EXPECT_EQ(r.targets, d.targets);
    EXPECT_EQ(r.input_names, d.input_names);
    EXPECT_EQ(r.input_units, d.input_units);
    EXPECT_EQ(r.target_names, d.target_names);
    EXPECT_EQ(r.target_units, d.target_units);
    EXPECT_EQ(r.generator, d.generator);
    EXPECT_EQ(r.generator_config, d.generator_config);
    EXPECT_EQ(r.content_hash(), d.content_hash());
  }
}

// Reads the file through the raw HDF5 C API, not the wrapper classes.
TEST(DatasetFile, ReadableByPlainHdf5CApi) {
  TempDir dir;
  const Dataset d = mixed();
  write_dataset(dir / "d.h5", d);
  const hid_t file = H5Fopen((dir / "d.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t root = H5Gopen2(file, "/", H5P_DEFAULT);
  EXPECT_EQ(raw_string_attribute(root, "format"), "cnclab-dataset");
  EXPECT_EQ(raw_string_attribute(root, "content_hash"), d.content_hash());
  H5Gclose(root);
  for (const char* name : {"/inputs", "/targets"}) {
    const hid_t ds = H5Dopen2(file, name, H5P_DEFAULT);
    ASSERT_GE(ds, 0) << name;
    const hid_t space = H5Dget_space(ds);
    hsize_t dims[2] = {0, 0};
    ASSERT_EQ(H5Sget_simple_extent_dims(space, dims, nullptr), 2);
    EXPECT_EQ(dims[0], 3u);  // samples
    EXPECT_EQ(dims[1], 2u);  // features
    double raw[3][2];
    ASSERT_GE(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw), 0);
    const Eigen::MatrixXd& m = std::string(name) == "/inputs" ? d.inputs : d.targets;
    for (int sample = 0; sample < 3; ++sample) {
      for (int feature = 0; feature < 2; ++feature) {
        EXPECT_EQ(raw[sample][feature], m(feature, sample)) << name;
      }
    }
    H5Sclose(space);
    H5Dclose(ds);
  }
  const hid_t inputs = H5Dopen2(file, "/inputs", H5P_DEFAULT);
  EXPECT_EQ(raw_string_attribute(inputs, "units"), "mixed: see /input_units");
  H5Dclose(inputs);
  const hid_t targets = H5Dopen2(file, "/targets", H5P_DEFAULT);
  EXPECT_EQ(raw_string_attribute(targets, "units"), "µm");
  H5Dclose(targets);
  H5Fclose(file);
}

TEST(DatasetFile, TamperedValueIsDetectedByHash) {
  TempDir dir;
  const auto path = dir / "d.h5";
  write_dataset(path, small());
  // One ulp of one value.
  edit_value(path, "/inputs", kSamples * kInputs, 7 * kInputs + 2,
             [](double x) { return std::nextafter(x, 2.0); });
  EXPECT_IO_ERROR(read_dataset(path), path.string() + ": content hash mismatch");
}

TEST(DatasetFile, MissingTextTruncatedOrForeignFilesAreIoErrorsNamingThem) {
  TempDir dir;
  EXPECT_IO_ERROR(read_dataset(dir / "missing.h5"), (dir / "missing.h5").string());

  std::ofstream(dir / "text.h5") << "samples: 1000\n";
  EXPECT_IO_ERROR(read_dataset(dir / "text.h5"), (dir / "text.h5").string());

  const auto truncated = dir / "truncated.h5";
  write_dataset(truncated, small());
  fs::resize_file(truncated, fs::file_size(truncated) / 2);
  EXPECT_IO_ERROR(read_dataset(truncated), truncated.string());

  const auto incomplete = dir / "incomplete.h5";
  write_dataset(incomplete, small());
  edit_raw(incomplete, [](hid_t file) { H5Adelete(file, "complete"); });
  EXPECT_IO_ERROR(read_dataset(incomplete), incomplete.string() + ": incomplete file");

  const auto other = dir / "other.h5";
  write_dataset(other, small());
  edit_raw(other, [](hid_t file) { H5Adelete(file, "format"); });
  EXPECT_IO_ERROR(read_dataset(other), other.string() + ": not a cnclab-dataset file");

  // A finished temporary of an interrupted write is still not a dataset.
  const auto partial = dir / ".d.h5.partial-1-0123456789abcdef";
  ASSERT_TRUE(is_partial_path(partial));
  write_dataset(dir / "d.h5", small());
  fs::copy_file(dir / "d.h5", partial);
  EXPECT_IO_ERROR(read_dataset(partial), partial.string());
}

TEST(DatasetFile, WrongShapeInTheFileIsAnIoError) {
  TempDir dir;
  const auto path = dir / "d.h5";
  write_dataset(path, small());
  edit_raw(path, [](hid_t file) {
    H5Ldelete(file, "/input_names", H5P_DEFAULT);
    const hsize_t n = 2;
    const hid_t space = H5Screate_simple(1, &n, nullptr);
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, 2);
    const hid_t ds =
        H5Dcreate2(file, "/input_names", type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, "x1x2");
    H5Dclose(ds);
    H5Tclose(type);
    H5Sclose(space);
  });
  // Written ASCII, null-terminated, as h5py does: readable, but too few names.
  EXPECT_IO_ERROR(read_dataset(path), path.string() + ": dataset inputs: 6 rows but 2 names");
}

TEST(DatasetFile, InvalidDatasetIsNotWrittenAndOldFileSurvives) {
  TempDir dir;
  const auto path = dir / "d.h5";
  const Dataset good = small();
  write_dataset(path, good);
  Dataset bad = good;
  bad.targets(0, 3) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(write_dataset(path, bad), Error);
  EXPECT_EQ(read_dataset(path).content_hash(), good.content_hash());
  for (const auto& e : fs::directory_iterator(dir.path())) {
    EXPECT_FALSE(is_partial_path(e.path())) << e.path();
  }
}

TEST(Dataset, ValidateNamesNonFiniteMatrixFeatureAndSample) {
  Dataset d = small();
  d.inputs(4, 11) = std::nan("");
  try {
    d.validate();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("inputs: x5 of sample 11 is nan"), std::string::npos)
        << e.what();
  }
  d = small();
  d.targets(0, 19) = -std::numeric_limits<double>::infinity();
  try {
    d.validate();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("targets: y of sample 19 is -inf"), std::string::npos)
        << e.what();
  }
}

TEST(Dataset, ValidateChecksSizes) {
  Dataset d = small();
  EXPECT_NO_THROW(d.validate());
  EXPECT_EQ(d.num_samples(), static_cast<std::size_t>(kSamples));
  d.input_units.pop_back();
  EXPECT_THROW(d.validate(), Error);
  d = small();
  d.targets.resize(1, kSamples - 1);
  d.targets.setZero();
  EXPECT_THROW(d.validate(), Error);
}

TEST(Dataset, HashChangesWithAnyPartOfTheContent) {
  const Dataset base = small();
  const auto h = base.content_hash();
  EXPECT_EQ(small().content_hash(), h);  // same content, same hash
  Dataset d = base;
  d.targets(0, 0) = std::nextafter(d.targets(0, 0), 1e9);
  EXPECT_NE(d.content_hash(), h);
  d = base;
  d.inputs(5, 19) = std::nextafter(d.inputs(5, 19), -1.0);
  EXPECT_NE(d.content_hash(), h);
  d = base;
  d.input_units[0] = "mm";
  EXPECT_NE(d.content_hash(), h);
  d = base;
  d.target_names[0] = "z";
  EXPECT_NE(d.content_hash(), h);
  // Moving a character across a name boundary changes the hash.
  Dataset a = mixed(), b = mixed();
  a.input_names = {"ab", "c"};
  b.input_names = {"a", "bc"};
  EXPECT_NE(a.content_hash(), b.content_hash());
}

TEST(DatasetFile, MetadataRoundTripsAndEntersTheHash) {
  TempDir dir;
  const Dataset d = with_metadata();
  write_dataset(dir / "m.h5", d);
  const Dataset r = read_dataset(dir / "m.h5");
  EXPECT_EQ(r.metadata, d.metadata);
  EXPECT_EQ(r.metadata_names, d.metadata_names);
  EXPECT_EQ(r.metadata_units, d.metadata_units);
  EXPECT_EQ(r.content_hash(), d.content_hash());
  EXPECT_NE(d.content_hash(), mixed().content_hash());
  Dataset changed = d;
  changed.metadata(1, 2) = 0.75;
  EXPECT_NE(changed.content_hash(), d.content_hash());
  // Datasets without metadata keep their hash (files written before metadata).
  Dataset none = mixed();
  none.metadata.resize(0, 3);
  EXPECT_EQ(none.content_hash(), mixed().content_hash());
  EXPECT_EQ(r.metadata_row("u_i"), 1);
  EXPECT_EQ(r.metadata_row("convex"), -1);
}

TEST(DatasetFile, TamperedMetadataIsDetectedByHash) {
  TempDir dir;
  const auto path = dir / "m.h5";
  write_dataset(path, with_metadata());
  edit_value(path, "/metadata", 6, 4, [](double) { return 7.0; });
  EXPECT_IO_ERROR(read_dataset(path), path.string() + ": content hash mismatch");
}

TEST(DatasetFile, MetadataOfTheWrongSizeIsRejected) {
  Dataset d = with_metadata();
  d.metadata.conservativeResize(2, 2);
  EXPECT_THROW(d.validate(), Error);
  d = with_metadata();
  d.metadata_units.pop_back();
  EXPECT_THROW(d.validate(), Error);
  d = with_metadata();
  d.metadata(0, 1) = NAN;
  EXPECT_THROW(d.validate(), Error);
}

// A version-1 file (the layout before metadata) still reads; unknown newer
// versions do not.
TEST(DatasetFile, Version1FilesStillReadAndNewerVersionsAreRefused) {
  TempDir dir;
  const auto path = dir / "v1.h5";
  write_dataset(path, small());
  const auto set_version = [&](std::int64_t version) {
    edit_raw(path, [&](hid_t file) {
      const hid_t attr = H5Aopen(file, "format_version", H5P_DEFAULT);
      H5Awrite(attr, H5T_NATIVE_INT64, &version);
      H5Aclose(attr);
    });
  };
  set_version(1);
  EXPECT_EQ(read_dataset(path).content_hash(), small().content_hash());
  set_version(kDatasetFormatVersion + 1);
  EXPECT_IO_ERROR(read_dataset(path), "unsupported format_version 3 (expected 1 to 2)");
}

}  // namespace
}  // namespace cnclab
