// Writing result files (declared in result_file.hpp; layout: result_layout.hpp).
#include "cnclab/core/error.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/result_layout.hpp"
#include "cnclab/experiment/run_warnings.hpp"
#include "cnclab/experiment/sequence_metrics.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/io/file_format.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/nn/metrics.hpp"

namespace cnclab {

void write_result(const std::filesystem::path& path, const RunRecord& r) {
  AtomicOutput out(path);
  try {
    H5File f = H5File::create(out.temp_path());
    write_result_header(f, r);
    ResultLayoutWriter io(f);
    result_layout::training(io, r);
    write_metrics(f, r.metrics, training_metric_units(r));
    write_result_upstream(f, r.upstream);
    mark_complete(f);  // last
    f.close();
    out.commit();
  } catch (const IoError& e) {
    // Name the file the user asked for; the temporary is removed by `out`.
    throw IoError(path.string() + ": result not written: " + std::string(e.what()));
  }
}

void write_result_header(H5File& f, const RunRecord& r) {
  write_format(f, kResultFormat, kResultFormatVersion);
  if (r.kind != "train") f.set_attribute("/", "kind", r.kind);  // absent: train
  if (!r.warnings.empty()) f.set_attribute("/", "warnings", join_warnings(r.warnings));
  ResultLayoutWriter io(f);
  result_layout::header(io, r);
}

void write_result_upstream(H5File& f, const std::vector<UpstreamRef>& upstream) {
  ResultLayoutWriter io(f);
  result_layout::upstream(io, upstream);
}

void write_metrics(H5File& f, const std::map<std::string, double>& metrics,
                   const std::map<std::string, std::string>& units) {
  // Numbers only in /metrics, so {k: float(v) for k, v in f["metrics"].attrs.items()}
  // works in h5py; the units beside them, one per metric ("" unknown).
  std::map<std::string, std::string> unit_of;
  for (const auto& [name, value] : metrics) {
    const auto it = units.find(name);
    unit_of[name] = it == units.end() ? "" : it->second;
  }
  ResultLayoutWriter io(f);
  result_layout::metrics(io, metrics, unit_of);
}

std::map<std::string, std::string> training_metric_units(const RunRecord& r) {
  std::map<std::string, std::string> units;
  for (const auto& [name, value] : r.metrics) {
    units[name] =
        r.narx ? sequence_metric_unit(metric_base(name)) : metric_unit(name, r.target_units);
  }
  return units;
}

}  // namespace cnclab
