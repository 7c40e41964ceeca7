#include "cnclab/experiment/trainer_spec.hpp"

#include <algorithm>
#include <iterator>
#include <type_traits>

#include "cnclab/core/fields.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/experiment/spec_text.hpp"

namespace cnclab {
namespace {

// In the order of TrainerSpec's alternatives.
constexpr const char* kTrainerNames[] = {"sgdm", "lm", "trainbr"};

SgdmOptions read_sgdm(const ConfigReader& r) {
  SgdmOptions t;
  sgdm_fields().read(r, t);
  r.validate([&] { t.validate(); });
  return t;
}

template <class Options>
Options read_lm(const ConfigReader& r, Options t = {}) {
  lm_fields().read(r, t);
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
          sgdm_fields().emit(out, t);
        } else {
          lm_fields().emit(out, t);
        }
      },
      trainer);
  out << YAML::EndMap;
}

}  // namespace cnclab
