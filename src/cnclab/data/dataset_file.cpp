#include "cnclab/data/dataset_file.hpp"

#include "cnclab/core/error.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/io/file_format.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/io/isolated_read.hpp"

namespace cnclab {

namespace {
// The `units` attribute of a matrix: the unit all its features share, or a
// pointer to the per-feature list when they differ.
std::string common_unit(const std::vector<std::string>& units, const std::string& list) {
  for (const auto& u : units) {
    if (u != units.front()) return "mixed: see " + list;
  }
  return units.empty() ? "1" : units.front();
}
}  // namespace

void write_dataset(const std::filesystem::path& path, const Dataset& d) {
  d.validate();
  AtomicOutput out(path);
  try {
    H5File f = H5File::create(out.temp_path());
    write_format(f, kDatasetFormat, kDatasetFormatVersion);
    f.set_attribute("/", "generator", d.generator);
    f.set_attribute("/", "content_hash", d.content_hash());
    f.write_matrix("/inputs", d.inputs, common_unit(d.input_units, "/input_units"));
    f.write_matrix("/targets", d.targets, common_unit(d.target_units, "/target_units"));
    f.write_strings("/input_names", d.input_names);
    f.write_strings("/input_units", d.input_units);
    f.write_strings("/target_names", d.target_names);
    f.write_strings("/target_units", d.target_units);
    f.write_string("/generator_config", d.generator_config);
    if (d.has_metadata()) {
      f.write_matrix("/metadata", d.metadata, common_unit(d.metadata_units, "/metadata_units"));
      f.write_strings("/metadata_names", d.metadata_names);
      f.write_strings("/metadata_units", d.metadata_units);
    }
    mark_complete(f);
    f.close();
    out.commit();
  } catch (const IoError& e) {
    // Name the file the user asked for; the temporary is removed by `out`.
    throw IoError(path.string() + ": dataset not written: " + std::string(e.what()));
  }
}

namespace {
Dataset read_dataset_in_process(const std::filesystem::path& path);
}  // namespace

Dataset read_dataset(const std::filesystem::path& path) {
  probe_in_child(path, [&] { read_dataset_in_process(path); });
  return read_dataset_in_process(path);
}

namespace {
Dataset read_dataset_in_process(const std::filesystem::path& path) {
  const H5File f = H5File::open_read(path);
  const auto bad = [&](const std::string& what) { throw IoError(path.string() + ": " + what); };
  const int version =
      require_format(f, kDatasetFormat, kDatasetOldestFormatVersion, kDatasetFormatVersion);
  Dataset d;
  d.inputs = f.read_matrix("/inputs");
  d.targets = f.read_matrix("/targets");
  d.input_names = f.read_strings("/input_names");
  d.input_units = f.read_strings("/input_units");
  d.target_names = f.read_strings("/target_names");
  d.target_units = f.read_strings("/target_units");
  d.generator = f.attribute_string("/", "generator");
  d.generator_config = f.read_string("/generator_config");
  if (version >= 2 && f.exists("/metadata")) {
    d.metadata = f.read_matrix("/metadata");
    d.metadata_names = f.read_strings("/metadata_names");
    d.metadata_units = f.read_strings("/metadata_units");
  }
  try {
    d.validate();
  } catch (const Error& e) {
    bad(e.what());
  }
  if (d.content_hash() != f.attribute_string("/", "content_hash")) {
    bad("content hash mismatch: the data were modified or corrupted after writing");
  }
  return d;
}
}  // namespace

}  // namespace cnclab
