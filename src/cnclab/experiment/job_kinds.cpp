#include "cnclab/experiment/job_kinds.hpp"

#include <stdexcept>
#include <utility>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/experiment/spec.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

std::vector<JobKind>& job_kind_registry() {
  static std::vector<JobKind> kinds;
  return kinds;
}

std::string known_kinds() {
  std::string s = "train";
  for (const auto& k : job_kind_registry()) s += ", " + k.kind;
  return s;
}

}  // namespace

void register_job_kind(JobKind kind) {
  if (kind.kind == "train" || find_job_kind(kind.kind)) {
    throw std::logic_error("job kind '" + kind.kind + "' registered twice");
  }
  job_kind_registry().push_back(std::move(kind));
}

const std::vector<JobKind>& registered_job_kinds() {
  return job_kind_registry();
}

std::optional<JobKind> find_job_kind(const std::string& kind) {
  for (const auto& k : job_kind_registry()) {
    if (k.kind == kind) return k;
  }
  return std::nullopt;
}

std::string experiment_kind(const fs::path& file) {
  const ConfigDocument doc = ConfigDocument::load(file);
  const ConfigReader root = doc.root();
  const auto kind = root.get<std::string>("kind", "train");
  if (kind != "train" && !find_job_kind(kind)) {
    root.fail("kind", "unknown kind; known: " + known_kinds());
  }
  return kind;
}

std::vector<FieldInfo> job_file_fields(const std::string& kind) {
  FieldInfo k = custom_info("kind", "this job's kind", FieldKind::string, Rule::one_of({kind}));
  k.required = true;
  std::vector<FieldInfo> fields = {k};
  for (const auto& f : experiment_fields().info()) {
    if (f.key == "name" || f.key == "description") fields.push_back(f);
  }
  return fields;
}

}  // namespace cnclab
