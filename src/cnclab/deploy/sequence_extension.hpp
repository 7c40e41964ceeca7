#pragma once
// What a study adds to `cnclab predict` and `cnclab export` for the narx
// models trained on one dataset generator. The deploy module knows no
// generator by name: a study registers its extension from its
// register_<paper>_study() (src/cli/builtins.cpp), as it registers job kinds
// and tables. Seed 002's (studies/contour_error/contour_deployment.hpp):
// the physical velocity and following error behind the following_error
// dataset's scaled columns, and the Taylor contour error estimate (Eqs. 3-6)
// per tick from the predicted following errors.
#include <Eigen/Core>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "cnclab/data/dataset.hpp"
#include "cnclab/deploy/code_text.hpp"
#include "cnclab/deploy/deployed_model.hpp"
#include "cnclab/deploy/named_column.hpp"

namespace cnclab {

// Extra code of an export (the Taylor estimate of seed 002).
struct ExtraCode {
  std::string c_declarations;            // into NAME.h, after the model's API
  std::string c_definitions;             // into NAME.c, after the model's functions
  std::string torch_methods;             // methods of the torch module, indented by 4 spaces
  std::vector<std::string> description;  // lines for the export's comment header
};

struct SequenceExtension {
  std::string generator;  // the registered name of the dataset generator it serves
  std::string owner;      // who registered it, for messages ("contour_error (seed 002)")
  // Fills model.physical_inputs and physical_targets (one per network, in
  // model.networks order) from the training dataset. Throws ConfigError
  // when the model's networks are not the ones it knows.
  std::function<void(const Dataset& training, DeployedModel& model)> physical_columns;
  // Columns besides the networks' inputs and targets that `per_tick` reads,
  // as (name, unit): from an input dataset's metadata, or a CSV's columns of
  // the same names.
  std::vector<std::pair<std::string, std::string>> context_columns;
  // Per-tick columns computed from the physical prediction `predicted` (one
  // series per network) labelled `label` ("closed_loop", "open_loop",
  // "measured") and the context columns the input has (by name). Empty when
  // a column it needs is missing.
  std::function<std::vector<NamedColumn>(
      const DeployedModel& model, const std::map<std::string, Eigen::VectorXd>& context,
      const std::vector<Eigen::VectorXd>& predicted, const std::string& label)>
      per_tick;
  // Extra code of the exports (C in the context's precision); may be empty.
  std::function<ExtraCode(const DeployedModel& model, const CCodeContext& c)> code;
};

// std::logic_error when the generator already has one.
void register_sequence_extension(SequenceExtension extension);
// The extension registered for `generator`, or null.
const SequenceExtension* find_sequence_extension(const std::string& generator);

}  // namespace cnclab
