#include "cnclab/train/summary.hpp"

#include "cnclab/core/enum_names.hpp"

namespace cnclab {
namespace {

constexpr EnumName<Termination> kTerminationNames[] = {
    {Termination::max_epochs, "max_epochs"},
    {Termination::early_stop, "early_stop"},
    {Termination::diverged, "diverged"},
    {Termination::stopped_by_callback, "stopped_by_callback"},
    {Termination::goal, "goal"},
    {Termination::min_gradient, "min_gradient"},
    {Termination::mu_max, "mu_max"}};

}  // namespace

std::string to_string(Termination t) {
  return enum_name(kTerminationNames, t);
}

bool parse_termination(const std::string& text, Termination& t) {
  const auto parsed = enum_value(kTerminationNames, text);
  if (parsed) t = *parsed;
  return parsed.has_value();
}

}  // namespace cnclab
