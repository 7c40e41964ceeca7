#include "cnclab/train/trainer_registry.hpp"

#include <algorithm>

namespace cnclab {

void TrainerRegistry::add(TrainerDef def) {
  if (def.name.empty() || find(def.name) != nullptr) {
    throw std::logic_error("TrainerRegistry: trainer '" + def.name +
                           "' is unnamed or registered twice");
  }
  if (!def.defaults || !def.read || !def.to_node || !def.keys || !def.fields || !def.epochs ||
      !def.with_epochs || !def.train_mlp || !def.workspace_bytes ||
      def.capabilities.needs_jacobian != static_cast<bool>(def.train_residual)) {
    throw std::logic_error("TrainerRegistry: trainer '" + def.name +
                           "' lacks a function (train_residual exactly when needs_jacobian)");
  }
  defs_.push_back(std::move(def));
}

const TrainerDef* TrainerRegistry::find(const std::string& name) const {
  const auto it =
      std::find_if(defs_.begin(), defs_.end(), [&](const TrainerDef& d) { return d.name == name; });
  return it == defs_.end() ? nullptr : &*it;
}

std::vector<std::string> TrainerRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& d : defs_) out.push_back(d.name);
  return out;
}

}  // namespace cnclab
