#pragma once
// The trainers an experiment can name in `trainer: {type: ...}`. Each trainer
// declares itself once, in its own files, as a TrainerDef: its name, its
// fields (core/fields.hpp) with their defaults, what it supports, how it
// trains a network (and, for Jacobian trainers, any residual objective) and
// the layout of its history. The spec reader, the JSON Schema, the dispatch,
// the result files and `show` take everything from the registry; none of
// them names a trainer.
//
// Adding a trainer: write train/<name>.{hpp,cpp} with its options struct,
// its FieldList and a `TrainerDef <name>_trainer()` built by make_trainer(),
// and add it in builtin_trainers.cpp.
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <any>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "cnclab/core/config.hpp"
#include "cnclab/core/field_info.hpp"
#include "cnclab/core/fields.hpp"
#include "cnclab/nn/mlp.hpp"
#include "cnclab/train/lm.hpp"
#include "cnclab/train/residual_objective.hpp"
#include "cnclab/train/summary.hpp"

namespace cnclab {

// What a trainer supports; the readers and checks ask these, never a name.
struct TrainerCapabilities {
  bool dropout = false;          // trains a network with dropout (a stochastic objective)
  bool mini_batches = false;     // updates per mini-batch (batch_size)
  bool validation_stop = false;  // can stop on the validation loss
  bool needs_jacobian = false;   // works on residuals and their Jacobian (any ResidualObjective)
  bool deterministic = false;    // uses no random stream: same data, same weights
  bool float32 = false;          // has a float32 training loop (precision: float32)
};

// What a trainer records per epoch beyond Summary::history (EpochRecord):
// result files store and `show` prints it accordingly.
enum class TrainerHistory {
  epochs,               // EpochRecord only
  levenberg_marquardt,  // + Summary::lm_history (sse, ssw, mu, gradient, ...)
  bayesian,             // as levenberg_marquardt, with alpha, beta, gamma meaningful
};

// Called by every trainer's epoch loop.
struct TrainingHooks {
  // Loss on held-out data at the end of each epoch (evaluation mode); empty = none.
  std::function<double(const Eigen::VectorXd& params)> validation_loss;
  // After every epoch; returning false stops training.
  std::function<bool(const EpochRecord&, const Eigen::VectorXd& params)> on_epoch;
};

// A network to train on (normalised) data: x inputs x samples, y outputs x
// samples. The random streams of a trainer derive from `seed` (e.g.
// Rng(seed, "dropout"), Rng(seed, "shuffle")).
struct MlpTrainingProblem {
  const Mlp& mlp;
  const Eigen::MatrixXd& x;
  const Eigen::MatrixXd& y;
  std::uint64_t seed = 0;
  TrainingHooks hooks;
};

struct TrainerDef {
  std::string name;     // the value of trainer.type
  std::string summary;  // one line for `cnclab schema` and errors
  TrainerCapabilities capabilities;
  TrainerHistory history = TrainerHistory::epochs;
  // Why there is no validation stop, for `show` ("as MATLAB's trainbr");
  // used when !capabilities.validation_stop.
  std::string without_validation_stop;

  // Type-erased over the trainer's options struct (std::any holds it).
  std::function<std::any()> defaults;
  std::function<std::any(const ConfigReader&)> read;  // fields read, then validated
  std::function<YAML::Node(const std::any&)> to_node;
  std::function<std::vector<std::string>()> keys;
  std::function<std::vector<FieldInfo>()> fields;  // with the trainer's defaults
  std::function<std::size_t(const std::any&)> epochs;
  std::function<std::any(const std::any&, std::size_t epochs)> with_epochs;  // a copy with `epochs`
  std::function<Summary(const std::any&, const MlpTrainingProblem&, Eigen::VectorXd& params)>
      train_mlp;
  // needs_jacobian trainers: any residual objective (a NARX network's);
  // empty otherwise.
  std::function<Summary(const std::any&, ResidualObjective&, Eigen::VectorXd& params,
                        const LmHooks&)>
      train_residual;
  // Bytes needed beyond the network and data, for `parameters` weights.
  std::function<double(double parameters)> workspace_bytes = [](double) { return 0.0; };
};

// A TrainerDef over the options struct `Options` (with `epochs` and
// validate()) and its field list (declared over Options or a base of it);
// `train(options, problem, params)` trains an MLP problem.
template <class Options, class Fields, class Train>
TrainerDef make_trainer(std::string name, std::string summary, const FieldList<Fields>& fields,
                        TrainerCapabilities capabilities, TrainerHistory history, Train train) {
  TrainerDef d;
  d.name = std::move(name);
  d.summary = std::move(summary);
  d.capabilities = capabilities;
  d.history = history;
  static_assert(std::is_base_of_v<Fields, Options>);
  const FieldList<Fields>* f = &fields;  // field lists live for the program
  d.defaults = [] { return std::any(Options{}); };
  d.read = [f](const ConfigReader& r) {
    Options o;
    f->read(r, o);
    r.validate([&] { o.validate(); });
    return std::any(o);
  };
  d.to_node = [f](const std::any& o) { return f->to_node(std::any_cast<const Options&>(o)); };
  d.keys = [f] { return f->keys(); };
  d.fields = [f] { return f->info(Options{}); };
  d.epochs = [](const std::any& o) { return std::any_cast<const Options&>(o).epochs; };
  d.with_epochs = [](const std::any& o, std::size_t epochs) {
    Options copy = std::any_cast<const Options&>(o);
    copy.epochs = epochs;
    return std::any(copy);
  };
  d.train_mlp = [train](const std::any& o, const MlpTrainingProblem& p, Eigen::VectorXd& params) {
    return train(std::any_cast<const Options&>(o), p, params);
  };
  return d;
}

// The trainers in registration order (the first is the default type).
class TrainerRegistry {
 public:
  // std::logic_error for a name registered twice or a def without its functions.
  void add(TrainerDef def);
  // nullptr when `name` is not registered.
  const TrainerDef* find(const std::string& name) const;
  const std::vector<TrainerDef>& all() const { return defs_; }
  std::vector<std::string> names() const;

 private:
  std::vector<TrainerDef> defs_;
};

// The built-in trainers (builtin_trainers.cpp), filled once and never changed.
const TrainerRegistry& trainers();

}  // namespace cnclab
