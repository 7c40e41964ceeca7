#include "cnclab/train/summary.hpp"

namespace cnclab {

std::string to_string(Termination t) {
  switch (t) {
    case Termination::max_epochs:
      return "max_epochs";
    case Termination::early_stop:
      return "early_stop";
    case Termination::diverged:
      return "diverged";
    case Termination::stopped_by_callback:
      return "stopped_by_callback";
    case Termination::goal:
      return "goal";
    case Termination::min_gradient:
      return "min_gradient";
    case Termination::mu_max:
      return "mu_max";
  }
  return "?";
}

bool parse_termination(const std::string& text, Termination& t) {
  for (auto candidate : {Termination::max_epochs, Termination::early_stop, Termination::diverged,
                         Termination::stopped_by_callback, Termination::goal,
                         Termination::min_gradient, Termination::mu_max}) {
    if (to_string(candidate) == text) {
      t = candidate;
      return true;
    }
  }
  return false;
}

}  // namespace cnclab
