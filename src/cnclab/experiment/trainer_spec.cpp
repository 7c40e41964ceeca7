#include "cnclab/experiment/trainer_spec.hpp"

#include <algorithm>
#include <iterator>
#include <type_traits>

#include "cnclab/core/format.hpp"
#include "cnclab/experiment/spec_text.hpp"

namespace cnclab {
namespace {

// In the order of TrainerSpec's alternatives.
constexpr const char* kTrainerNames[] = {"sgdm", "lm", "trainbr"};

SgdmOptions read_sgdm(const ConfigReader& r) {
  SgdmOptions t;
  t.learning_rate = r.get<double>("learning_rate", t.learning_rate);
  t.momentum = r.get<double>("momentum", t.momentum);
  t.batch_size = r.get<std::size_t>("batch_size", t.batch_size);
  t.epochs = r.get<std::size_t>("epochs", t.epochs);
  t.shuffle = r.get<bool>("shuffle", t.shuffle);
  t.early_stop_patience = r.get<std::size_t>("early_stop_patience", t.early_stop_patience);
  r.validate([&] { t.validate(); });
  return t;
}

template <class Options>
Options read_lm(const ConfigReader& r, Options t = {}) {
  t.epochs = r.get<std::size_t>("epochs", t.epochs);
  t.goal = r.get<double>("goal", t.goal);
  t.mu = r.get<double>("mu", t.mu);
  t.mu_dec = r.get<double>("mu_dec", t.mu_dec);
  t.mu_inc = r.get<double>("mu_inc", t.mu_inc);
  t.mu_max = r.get<double>("mu_max", t.mu_max);
  t.min_gradient = r.get<double>("min_gradient", t.min_gradient);
  r.validate([&] { t.validate(); });
  return t;
}

}  // namespace

TrainbrOptions read_trainbr_options(const ConfigReader& r, const TrainbrOptions& start) {
  return read_lm<TrainbrOptions>(r, start);
}

std::string trainer_name(const TrainerSpec& trainer) {
  return kTrainerNames[trainer.index()];
}

bool is_trainer_name(const std::string& name) {
  return std::find(std::begin(kTrainerNames), std::end(kTrainerNames), name) !=
         std::end(kTrainerNames);
}

std::size_t trainer_epochs(const TrainerSpec& trainer) {
  return std::visit([](const auto& t) { return t.epochs; }, trainer);
}

bool is_levenberg_marquardt(const TrainerSpec& trainer) {
  return !std::holds_alternative<SgdmOptions>(trainer);
}

TrainerSpec read_trainer(const ConfigReader& r) {
  const auto type =
      choice(r, "type", "sgdm",
             std::vector<std::string>(std::begin(kTrainerNames), std::end(kTrainerNames)));
  if (type == "lm") return read_lm<LmOptions>(r);
  if (type == "trainbr") return read_lm<TrainbrOptions>(r);
  return read_sgdm(r);
}

void emit_trainer(YAML::Emitter& out, const TrainerSpec& trainer) {
  using YAML::Key, YAML::Value;
  out << YAML::BeginMap << Key << "type" << Value << trainer_name(trainer);
  std::visit(
      [&](const auto& t) {
        using T = std::decay_t<decltype(t)>;
        if constexpr (std::is_same_v<T, SgdmOptions>) {
          out << Key << "learning_rate" << Value << shortest_double(t.learning_rate);
          out << Key << "momentum" << Value << shortest_double(t.momentum);
          out << Key << "batch_size" << Value << t.batch_size;
          out << Key << "epochs" << Value << t.epochs;
          out << Key << "shuffle" << Value << t.shuffle;
          out << Key << "early_stop_patience" << Value << t.early_stop_patience;
        } else {
          out << Key << "epochs" << Value << t.epochs;
          out << Key << "goal" << Value << shortest_double(t.goal);
          out << Key << "mu" << Value << shortest_double(t.mu);
          out << Key << "mu_dec" << Value << shortest_double(t.mu_dec);
          out << Key << "mu_inc" << Value << shortest_double(t.mu_inc);
          out << Key << "mu_max" << Value << shortest_double(t.mu_max);
          out << Key << "min_gradient" << Value << shortest_double(t.min_gradient);
        }
      },
      trainer);
  out << YAML::EndMap;
}

}  // namespace cnclab
