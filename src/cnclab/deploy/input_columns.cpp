#include "cnclab/deploy/input_columns.hpp"

#include <algorithm>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/deploy/sequence_extension.hpp"

namespace cnclab {
namespace {

// One way of naming a model's columns: the dataset's names, or the physical ones.
struct ColumnSet {
  std::vector<std::string> names, units;
  const std::vector<ColumnScaling>* scaling = nullptr;  // physical: mapped to the dataset's units
  std::string what;                                     // "dataset" / "physical"
};

std::vector<ColumnSet> column_sets(const DeployedModel& m, bool targets) {
  std::vector<ColumnSet> sets;
  if (m.has_physical_columns()) {
    ColumnSet p{{}, {}, targets ? &m.physical_targets : &m.physical_inputs, "physical"};
    for (const auto& c : *p.scaling) {
      p.names.push_back(c.name);
      p.units.push_back(c.unit);
    }
    sets.push_back(std::move(p));
  }
  sets.push_back({targets ? m.target_names : m.input_names,
                  targets ? m.target_units : m.input_units, nullptr, "dataset"});
  return sets;
}

std::string listed(const ColumnSet& s) {
  std::vector<std::string> items;
  for (std::size_t i = 0; i < s.names.size(); ++i)
    items.push_back(s.names[i] + " [" + s.units[i] + "]");
  return join(items, ", ");
}

std::size_t present(const ColumnSet& s, const PredictionInput& in) {
  return static_cast<std::size_t>(std::count_if(
      s.names.begin(), s.names.end(), [&](const std::string& n) { return in.find(n) != nullptr; }));
}

// Rows of `set` over `samples`, checked for units and mapped to the dataset's units.
Eigen::MatrixXd read_set(const ColumnSet& set, const PredictionInput& in,
                         const std::vector<std::size_t>& samples) {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(set.names.size()),
                      static_cast<Eigen::Index>(samples.size()));
  for (std::size_t i = 0; i < set.names.size(); ++i) {
    const NamedColumn& c = *in.find(set.names[i]);
    if (!c.unit.empty() && c.unit != set.units[i]) {
      throw ConfigError(in.source + ": column " + c.name + " is in " + c.unit +
                        ", the network reads it in " + set.units[i]);
    }
    for (std::size_t s = 0; s < samples.size(); ++s) {
      const double x = c.values[static_cast<Eigen::Index>(samples[s])];
      out(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(s)) =
          set.scaling ? (*set.scaling)[i].to_dataset(x) : x;
    }
  }
  return out;
}

// The first set the input has completely; for targets none at all is fine
// (nullptr). ConfigError for a partial one.
const ColumnSet* choose(const std::vector<ColumnSet>& sets, const PredictionInput& in,
                        const char* what, bool optional) {
  for (const auto& s : sets) {
    if (present(s, in) == s.names.size()) return &s;
  }
  std::size_t best = 0;
  const ColumnSet* partial = nullptr;
  for (const auto& s : sets) {
    if (present(s, in) > best) best = present(s, in), partial = &s;
  }
  if (optional && partial == nullptr) return nullptr;
  const ColumnSet& s = partial ? *partial : sets.back();
  std::vector<std::string> missing;
  for (const auto& n : s.names) {
    if (in.find(n) == nullptr) missing.push_back(n);
  }
  std::string alternatives;
  for (const auto& other : sets) {
    if (&other != &s) alternatives += " (or the " + other.what + " columns " + listed(other) + ")";
  }
  throw ConfigError(in.source + ": the network reads " + std::to_string(s.names.size()) + " " +
                    what + " columns, " + listed(s) + alternatives + "; the input has " +
                    std::to_string(present(s, in)) + " of them, not " + join(missing, ", "));
}

// A CSV holds only columns the model knows (a misspelt name is an error,
// never an ignored column).
void check_known_columns(const DeployedModel& m, const PredictionInput& in) {
  std::vector<std::string> known;
  for (bool targets : {false, true}) {
    for (const auto& s : column_sets(m, targets))
      known.insert(known.end(), s.names.begin(), s.names.end());
  }
  if (m.extension) {
    for (const auto& [name, unit] : m.extension->context_columns) known.push_back(name);
  }
  for (const auto& c : in.columns) {
    if (std::find(known.begin(), known.end(), c.name) == known.end()) {
      throw ConfigError(in.source + ": column '" + c.name +
                        "' is not one the network reads; known columns: " + join(known, ", "));
    }
  }
}

std::vector<std::size_t> split_samples(const DeployedModel& m, const PredictionInput& in,
                                       const std::string& split) {
  std::vector<std::size_t> all(in.samples);
  for (std::size_t i = 0; i < in.samples; ++i) all[i] = i;
  if (split == "all") return all;
  const std::vector<std::size_t>* part = split == "train"        ? &m.split.train
                                         : split == "validation" ? &m.split.validation
                                         : split == "test"       ? &m.split.test
                                                                 : nullptr;
  if (part == nullptr) {
    throw ConfigError("--split " + split + ": must be all, train, validation or test");
  }
  if (in.kind == InputKind::csv || in.hash != m.dataset_hash) {
    throw ConfigError("--split " + split + ": " + in.source +
                      " is not the result's training dataset (content hash " + in.hash +
                      ", the result's " + m.dataset_hash + "); a split is of that dataset only");
  }
  if (part->empty()) {
    throw ConfigError("--split " + split + ": the result's " + split + " part is empty" +
                      (m.kind == ModelKind::narx
                           ? " (a narx result trains on the first half and validates on the "
                             "second: --split validation)"
                           : ""));
  }
  return *part;
}

}  // namespace

ModelColumns model_columns(const DeployedModel& m, const PredictionInput& in,
                           const std::string& split) {
  if (in.kind != InputKind::csv && in.generator != m.generator) {
    throw ConfigError(in.source + ": a dataset of generator " + in.generator +
                      "; the network was trained on " + m.generator + " data");
  }
  if (in.kind == InputKind::csv) check_known_columns(m, in);
  ModelColumns out;
  out.samples = split_samples(m, in, split);
  const auto input_sets = column_sets(m, false), target_sets = column_sets(m, true);
  const ColumnSet* inputs = choose(input_sets, in, "input", false);
  out.inputs = read_set(*inputs, in, out.samples);
  out.notes.push_back("inputs: the " + inputs->what + " columns " + listed(*inputs));
  if (const ColumnSet* targets = choose(target_sets, in, "target", true)) {
    out.targets = read_set(*targets, in, out.samples);
    out.notes.push_back("measured: the " + targets->what + " columns " + listed(*targets));
  } else {
    out.targets.resize(0, static_cast<Eigen::Index>(out.samples.size()));
    out.notes.push_back("measured: none (the input has no target column)");
  }
  if (m.extension) {
    for (const auto& [name, unit] : m.extension->context_columns) {
      const NamedColumn* c = in.find(name);
      if (c == nullptr) continue;
      if (!c->unit.empty() && c->unit != unit) {
        throw ConfigError(in.source + ": column " + name + " is in " + c->unit + ", expected " +
                          unit);
      }
      Eigen::VectorXd v(static_cast<Eigen::Index>(out.samples.size()));
      for (std::size_t s = 0; s < out.samples.size(); ++s) {
        v[static_cast<Eigen::Index>(s)] = c->values[static_cast<Eigen::Index>(out.samples[s])];
      }
      out.context[name] = std::move(v);
    }
  }
  return out;
}

}  // namespace cnclab
