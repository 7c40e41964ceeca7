#include "cnclab/experiment/job_result.hpp"

#include <algorithm>
#include <iomanip>
#include <stdexcept>

#include "cnclab/core/error.hpp"
#include "cnclab/core/hash.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/run_warnings.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/io/file_format.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/io/provenance.hpp"
#include "cnclab/nn/metrics.hpp"

namespace cnclab {
namespace fs = std::filesystem;

RunRecord make_job_record(const std::string& kind, const ResultKey& key,
                          const JobRequest& request) {
  RunRecord r;
  r.kind = kind;
  r.experiment = key.name;
  r.resolved_yaml = key.resolved_yaml;
  r.config_hash = hash_hex(key.resolved_yaml);
  r.provenance = make_provenance(key.seed.value_or(0));
  r.provenance.status = "complete";
  r.provenance.overrides = request.overrides;
  r.provenance.profile = request.profile;
  if (!key.source_file.empty()) set_project(r.provenance, key.source_file.parent_path());
  return r;
}

void write_job_result(const fs::path& path, const RunRecord& r) {
  if (r.kind == "train") throw std::logic_error("write_job_result: a training record");
  AtomicOutput out(path);
  try {
    H5File f = H5File::create(out.temp_path());
    write_result_header(f, r);
    write_metrics(f, r.metrics, r.metric_units);
    write_result_upstream(f, r.upstream);
    std::vector<std::string> roles, files;
    for (const auto& o : r.outputs) {
      roles.push_back(o.role);
      files.push_back(o.file);
    }
    if (!r.outputs.empty()) {
      f.write_strings("/outputs/roles", roles);
      f.write_strings("/outputs/files", files);
    }
    f.create_group("/job");
    for (const auto& [name, text] : r.facts) f.set_attribute("/job", name, text);
    mark_complete(f);  // last
    f.close();
    out.commit();
  } catch (const IoError& e) {
    throw IoError(path.string() + ": result not written: " + std::string(e.what()));
  }
}

RunRecord read_job_result(const H5File& f) {
  RunRecord r;
  r.kind = f.attribute_string("/", "kind");
  r.experiment = f.attribute_string("/", "experiment");
  r.config_hash = f.attribute_string("/", "config_hash");
  r.resolved_yaml = f.read_string("/config");
  r.provenance = read_provenance(f, "/provenance");
  r.metrics = read_metrics(f);
  r.metric_units = read_metric_units(f);
  r.warnings = read_warnings(f);
  r.upstream = read_upstream(f);
  if (f.exists("/outputs")) {
    const auto roles = f.read_strings("/outputs/roles");
    const auto files = f.read_strings("/outputs/files");
    if (roles.size() != files.size()) {
      throw IoError(f.path().string() + ": /outputs: lists of different lengths");
    }
    for (std::size_t i = 0; i < roles.size(); ++i) r.outputs.push_back({roles[i], files[i]});
  }
  if (f.exists("/job")) {
    for (const auto& name : f.attribute_names("/job")) {
      r.facts[name] = f.attribute_string("/job", name);
    }
  }
  return r;
}

void print_job_result(const RunRecord& r, std::ostream& out, const ShowOptions& options) {
  const Provenance& p = r.provenance;
  out << "experiment   " << r.experiment << " (kind: " << r.kind << ")\n"
      << "status       " << status_text(p.status, r.warnings)
      << (p.failure_reason.empty() ? "" : ": " + p.failure_reason) << "\n";
  print_provenance(p, out);
  for (const auto& u : r.upstream) {
    out << "upstream     " << u.experiment << ": " << u.result_file << "\n";
  }
  for (const auto& o : r.outputs) out << "output       " << o.role << ": " << o.file << "\n";
  for (const auto& [name, text] : r.facts) out << "fact         " << name << ": " << text << "\n";
  print_metrics(r, "", out);
  print_result_config(r.resolved_yaml, out, options);
}

fs::path output_path(const RunRecord& record, const fs::path& result_file,
                     const std::string& role) {
  for (const auto& o : record.outputs) {
    if (o.role == role) return result_file.parent_path() / o.file;
  }
  throw IoError(result_file.string() + ": no output '" + role + "'");
}

}  // namespace cnclab
