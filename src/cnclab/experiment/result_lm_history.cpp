#include "cnclab/experiment/result_lm_history.hpp"

#include <cmath>
#include <vector>

#include "cnclab/core/error.hpp"

namespace cnclab {

void write_lm_history(H5File& f, const std::string& group, const Summary& s) {
  for (const auto& series : kLmSeries) {
    std::vector<double> v;
    for (const auto& e : s.lm_history) v.push_back(e.*series.field);
    f.write_vector(group + "/" + series.name, v, series.units);
    if (s.lm_initial) {
      f.set_attribute(group, std::string("initial_") + series.name, (*s.lm_initial).*series.field);
    }
  }
}

void read_lm_history(const H5File& f, const std::string& group, std::size_t epochs, Summary& s) {
  s.lm_history.assign(epochs, LmEpochRecord{});
  const bool has_initial = f.has_attribute(group, "initial_sse");
  if (has_initial) s.lm_initial = LmEpochRecord{};
  for (const auto& series : kLmSeries) {
    const std::string name = group + "/" + series.name;
    if (!series.required && !f.exists(name)) {
      for (auto& e : s.lm_history) e.*series.field = std::nan("");
    } else {
      const auto v = f.read_vector(name);
      if (v.size() != epochs) {
        throw IoError(f.path().string() + ": " + name + ": " + std::to_string(v.size()) +
                      " values for " + std::to_string(epochs) + " epochs");
      }
      for (std::size_t i = 0; i < v.size(); ++i) s.lm_history[i].*series.field = v[i];
    }
    if (!has_initial) continue;
    const std::string attr = std::string("initial_") + series.name;
    (*s.lm_initial).*series.field =
        f.has_attribute(group, attr) ? f.attribute_double(group, attr) : std::nan("");
  }
}

}  // namespace cnclab
