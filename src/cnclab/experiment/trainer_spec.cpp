#include "cnclab/experiment/trainer_spec.hpp"

#include <algorithm>

#include "cnclab/experiment/spec_text.hpp"

namespace cnclab {
namespace {

// Keys that the chosen trainer lacks but another trainer has, set in another
// place (file or override) than `type`: consumed and named in one note (what a
// switch of trainer.type leaves behind). Written next to the type they do not
// belong to, they stay unknown keys.
void drop_keys_of_other_trainers(const ConfigReader& r, const TrainerDef& chosen,
                                 std::vector<std::string>* notes) {
  const auto own = chosen.keys();
  std::string dropped;
  for (const auto& key : r.keys()) {
    if (key == "type" || std::find(own.begin(), own.end(), key) != own.end()) continue;
    if (r.location(key).file == r.location("type").file) continue;
    for (const auto& other : trainers().all()) {
      const auto theirs = other.keys();
      if (std::find(theirs.begin(), theirs.end(), key) != theirs.end()) {
        r.raw(key);  // consumed: not an unknown key
        dropped += (dropped.empty() ? "" : ", ") + key;
        break;
      }
    }
  }
  if (!dropped.empty() && notes) {
    notes->push_back(r.dotted("type") + " is " + chosen.name + ": dropped " + dropped +
                     " (keys of another trainer)");
  }
}

}  // namespace

TrainerSpec::TrainerSpec() : def(&trainers().all().front()), options(def->defaults()) {}

TrainerSpec::TrainerSpec(const TrainerDef& d, std::any o) : def(&d), options(std::move(o)) {}

std::string trainer_name(const TrainerSpec& trainer) {
  return trainer.def->name;
}

std::size_t trainer_epochs(const TrainerSpec& trainer) {
  return trainer.def->epochs(trainer.options);
}

const TrainerCapabilities& trainer_capabilities(const TrainerSpec& trainer) {
  return trainer.def->capabilities;
}

std::vector<std::string> trainer_names(const TrainerFilter& allowed) {
  std::vector<std::string> names;
  for (const auto& d : trainers().all()) {
    if (!allowed || allowed(d)) names.push_back(d.name);
  }
  return names;
}

TrainerSpec read_trainer(const ConfigReader& r, std::vector<std::string>* notes,
                         const TrainerFilter& allowed) {
  const auto names = trainer_names(allowed);
  const auto type = choice(r, "type", names.front(), names);
  const TrainerDef& def = *trainers().find(type);
  drop_keys_of_other_trainers(r, def, notes);
  return TrainerSpec(def, def.read(r));
}

YAML::Node trainer_to_node(const TrainerSpec& trainer) {
  YAML::Node n(YAML::NodeType::Map);
  n["type"] = trainer_name(trainer);
  for (const auto& kv : trainer.def->to_node(trainer.options)) n[kv.first.Scalar()] = kv.second;
  return n;
}

}  // namespace cnclab
