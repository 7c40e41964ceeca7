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

// lm and trainbr: their fields (trainbr's lack max_fail).
const FieldList<LmOptions>& fields_of(const std::string& type) {
  return type == "lm" ? lm_fields() : trainbr_fields();
}

template <class Options>
Options read_lm(const ConfigReader& r, Options t = {}) {
  fields_of(std::is_same_v<Options, TrainbrOptions> ? "trainbr" : "lm").read(r, t);
  r.validate([&] { t.validate(); });
  return t;
}

std::vector<std::string> trainer_keys(const std::string& type) {
  return type == "sgdm" ? sgdm_fields().keys() : fields_of(type).keys();
}

// Keys that the chosen trainer lacks but another trainer has, set in another
// place (file or override) than `type`: consumed and named in one note (what a
// switch of trainer.type leaves behind). Written next to the type they do not
// belong to, they stay unknown keys.
void drop_keys_of_other_trainers(const ConfigReader& r, const std::string& type,
                                 std::vector<std::string>* notes) {
  const auto own = trainer_keys(type);
  std::string dropped;
  for (const auto& key : r.keys()) {
    if (key == "type" || std::find(own.begin(), own.end(), key) != own.end()) continue;
    if (r.location(key).file == r.location("type").file) continue;
    for (const char* other : kTrainerNames) {
      const auto theirs = trainer_keys(other);
      if (std::find(theirs.begin(), theirs.end(), key) != theirs.end()) {
        r.raw(key);  // consumed: not an unknown key
        dropped += (dropped.empty() ? "" : ", ") + key;
        break;
      }
    }
  }
  if (!dropped.empty() && notes) {
    notes->push_back(r.dotted("type") + " is " + type + ": dropped " + dropped +
                     " (keys of another trainer)");
  }
}

}  // namespace

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

TrainerSpec read_trainer(const ConfigReader& r, std::vector<std::string>* notes) {
  const auto type =
      choice(r, "type", "sgdm",
             std::vector<std::string>(std::begin(kTrainerNames), std::end(kTrainerNames)));
  drop_keys_of_other_trainers(r, type, notes);
  if (type == "lm") return read_lm<LmOptions>(r);
  if (type == "trainbr") return read_lm<TrainbrOptions>(r);
  return read_sgdm(r);
}

YAML::Node trainer_to_node(const TrainerSpec& trainer) {
  YAML::Node n(YAML::NodeType::Map);
  n["type"] = trainer_name(trainer);
  std::visit(
      [&](const auto& t) {
        using T = std::decay_t<decltype(t)>;
        YAML::Node fields;
        if constexpr (std::is_same_v<T, SgdmOptions>) {
          fields = sgdm_fields().to_node(t);
        } else {
          fields = fields_of(std::is_same_v<T, TrainbrOptions> ? "trainbr" : "lm").to_node(t);
        }
        for (const auto& kv : fields) n[kv.first.Scalar()] = kv.second;
      },
      trainer);
  return n;
}

}  // namespace cnclab
