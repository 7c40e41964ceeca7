#include "cnclab/sweep/search_findings.hpp"

#include "cnclab/io/h5.hpp"
#include "cnclab/nn/metrics.hpp"

namespace cnclab {

constexpr const char* kEvaluator = "fanova";

void write_search_findings(H5File& f, const SearchFindings& s) {
  f.create_group("/importance");
  f.set_attribute("/importance", "evaluator", std::string(kEvaluator));
  f.set_attribute("/importance", "target", s.importance_target);
  if (s.importance_parameter.empty()) {
    f.set_attribute("/importance", "note", s.importance_note);
  } else {
    f.write_strings("/importance/parameter", s.importance_parameter);
    f.write_vector("/importance/value", s.importance_value);
  }
  if (s.multi_objective) {
    f.create_group("/pareto");
    f.set_attribute("/pareto", "objectives", s.objectives);
    f.write_strings("/pareto/trial", s.pareto);
  }
}

std::optional<SearchFindings> read_search_findings(const H5File& f) {
  if (!f.exists("/importance") && !f.exists("/pareto")) return std::nullopt;
  SearchFindings s;
  if (f.exists("/importance")) {
    if (f.has_attribute("/importance", "target"))
      s.importance_target = f.attribute_string("/importance", "target");
    if (f.has_attribute("/importance", "note"))
      s.importance_note = f.attribute_string("/importance", "note");
    if (f.exists("/importance/parameter")) {
      s.importance_parameter = f.read_strings("/importance/parameter");
      s.importance_value = f.read_vector("/importance/value");
    }
  }
  if (f.exists("/pareto")) {
    s.multi_objective = true;
    s.objectives = f.attribute_string("/pareto", "objectives");
    s.pareto = f.read_strings("/pareto/trial");
  }
  return s;
}

void print_search_findings(std::ostream& out, const SearchFindings& s) {
  if (s.importance_parameter.empty()) {
    out << "parameter importance (fANOVA): none (" << s.importance_note << ")\n";
  } else {
    out << "parameter importance (Optuna's fANOVA, of " << s.importance_target << "):\n";
    for (std::size_t i = 0; i < s.importance_parameter.size(); ++i) {
      out << "  " << s.importance_parameter[i] << "  " << format_metric(s.importance_value[i])
          << "\n";
    }
  }
  if (s.multi_objective) {
    out << "Pareto front (" << s.objectives << "): " << s.pareto.size() << " trial(s):";
    for (const auto& id : s.pareto) out << " " << id;
    out << "\n";
  }
}

}  // namespace cnclab
