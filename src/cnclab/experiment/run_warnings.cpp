#include "cnclab/experiment/run_warnings.hpp"

#include <algorithm>

#include "cnclab/core/format.hpp"
#include "cnclab/nn/constant_predictions.hpp"

namespace cnclab {
namespace {

constexpr const char* kSeparator = "; ";

std::string constant_warning(const std::vector<Eigen::Index>& rows, Eigen::Index outputs,
                             const std::vector<std::string>& names) {
  if (rows.empty()) return "";
  std::string w = kConstantPredictions;
  if (outputs < 2) return w;
  std::vector<std::string> which;
  for (Eigen::Index r : rows) {
    const auto i = static_cast<std::size_t>(r);
    which.push_back(i < names.size() ? names[i] : "output " + std::to_string(i + 1));
  }
  return w + " (" + join(which, ", ") + ")";
}

}  // namespace

std::vector<std::string> prediction_warnings(const RunRecord& r) {
  std::string w;
  if (r.narx) {
    const NarxRecord& n = *r.narx;
    const auto first = static_cast<Eigen::Index>(n.first_step);
    const Eigen::Index steps = std::max<Eigen::Index>(0, n.predictions.cols() - first);
    std::vector<std::string> axes;
    for (const auto& net : n.networks) axes.push_back(net.axis);
    w = constant_warning(
        constant_prediction_rows(n.predictions.rightCols(steps), n.targets.rightCols(steps)),
        n.predictions.rows(), axes);
  } else {
    w = constant_warning(constant_prediction_rows(r.test_predictions, r.test_targets),
                         r.test_predictions.rows(), r.target_names);
  }
  if (w.empty()) return {};
  return {w};
}

std::string status_text(const std::string& status, const std::vector<std::string>& warnings) {
  std::string s = status;
  for (const auto& w : warnings) s += "; warning: " + w;
  return s;
}

std::string join_warnings(const std::vector<std::string>& warnings) {
  return join(warnings, kSeparator);
}

std::vector<std::string> split_warnings(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find(kSeparator, start);
    out.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + std::string(kSeparator).size();
  }
  return out;
}

}  // namespace cnclab
