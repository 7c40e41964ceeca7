#include "cnclab/data/dataset.hpp"

#include <algorithm>
#include <cmath>

#include "cnclab/core/error.hpp"
#include "cnclab/core/hash.hpp"

namespace cnclab {
namespace {

void check_matrix(const Eigen::MatrixXd& m, const char* what, const std::vector<std::string>& names,
                  const std::vector<std::string>& units) {
  const auto rows = static_cast<std::size_t>(m.rows());
  if (names.size() != rows || units.size() != rows) {
    throw Error(std::string("dataset ") + what + ": " + std::to_string(rows) + " rows but " +
                std::to_string(names.size()) + " names and " + std::to_string(units.size()) +
                " units");
  }
  for (Eigen::Index j = 0; j < m.cols(); ++j) {
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
      if (!std::isfinite(m(i, j))) {
        throw Error(std::string("dataset ") + what + ": " + names[static_cast<std::size_t>(i)] +
                    " of sample " + std::to_string(j) + " is " + std::to_string(m(i, j)) +
                    " (values must be finite)");
      }
    }
  }
}

}  // namespace

void Dataset::validate() const {
  if (inputs.cols() != targets.cols()) {
    throw Error("dataset: " + std::to_string(inputs.cols()) + " input samples but " +
                std::to_string(targets.cols()) + " target samples");
  }
  check_matrix(inputs, "inputs", input_names, input_units);
  check_matrix(targets, "targets", target_names, target_units);
  if (has_metadata() && metadata.cols() != inputs.cols()) {
    throw Error("dataset: " + std::to_string(inputs.cols()) + " input samples but " +
                std::to_string(metadata.cols()) + " metadata samples");
  }
  check_matrix(metadata, "metadata", metadata_names, metadata_units);
}

Eigen::Index Dataset::metadata_row(const std::string& name) const {
  for (std::size_t i = 0; i < metadata_names.size(); ++i) {
    if (metadata_names[i] == name) return static_cast<Eigen::Index>(i);
  }
  return -1;
}

std::string Dataset::content_hash() const {
  Hasher h;
  const auto add_strings = [&](const std::vector<std::string>& v) {
    h.add(static_cast<std::uint64_t>(v.size()));
    for (const auto& s : v) h.add(static_cast<std::uint64_t>(s.size())).add(s);
  };
  h.add(static_cast<std::uint64_t>(inputs.rows())).add(static_cast<std::uint64_t>(inputs.cols()));
  h.add(static_cast<std::uint64_t>(targets.rows())).add(static_cast<std::uint64_t>(targets.cols()));
  add_strings(input_names);
  add_strings(input_units);
  add_strings(target_names);
  add_strings(target_units);
  add_strings({generator, generator_config});
  h.add(std::span<const double>(inputs.data(), static_cast<std::size_t>(inputs.size())));
  h.add(std::span<const double>(targets.data(), static_cast<std::size_t>(targets.size())));
  if (has_metadata()) {
    h.add(static_cast<std::uint64_t>(metadata.rows()))
        .add(static_cast<std::uint64_t>(metadata.cols()));
    add_strings(metadata_names);
    add_strings(metadata_units);
    h.add(std::span<const double>(metadata.data(), static_cast<std::size_t>(metadata.size())));
  }
  return h.hex();
}

Dataset select_targets(const Dataset& d, const std::vector<std::string>& names) {
  if (names.empty()) return d;
  std::string available;
  for (const auto& n : d.target_names) available += (available.empty() ? "" : ", ") + n;
  std::vector<Eigen::Index> rows;
  for (const auto& name : names) {
    const auto it = std::find(d.target_names.begin(), d.target_names.end(), name);
    if (it == d.target_names.end()) {
      throw ConfigError("dataset.targets: '" + name + "' is not a target of this dataset (" +
                        d.generator + " targets: " + available + ")");
    }
    const auto row = static_cast<Eigen::Index>(it - d.target_names.begin());
    if (std::find(rows.begin(), rows.end(), row) != rows.end()) {
      throw ConfigError("dataset.targets: '" + name + "' is listed twice");
    }
    rows.push_back(row);
  }
  Dataset out = d;
  out.targets.resize(static_cast<Eigen::Index>(rows.size()), d.targets.cols());
  out.target_names.clear();
  out.target_units.clear();
  for (std::size_t k = 0; k < rows.size(); ++k) {
    out.targets.row(static_cast<Eigen::Index>(k)) = d.targets.row(rows[k]);
    out.target_names.push_back(d.target_names[static_cast<std::size_t>(rows[k])]);
    out.target_units.push_back(d.target_units[static_cast<std::size_t>(rows[k])]);
  }
  return out;
}

}  // namespace cnclab
