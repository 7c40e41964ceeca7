// Fuzz target: experiment YAML text -> typed, validated spec.
// Contract: success, or cnclab::ConfigError whose message names the source
// ("fuzz.yaml..."). Any other exception, crash, leak or hang is a finding.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "cnclab/core/error.hpp"
#include "cnclab/experiment/spec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto loaded = cnclab::parse_experiment(text, "fuzz.yaml");
    // What validate prints must itself load to the same resolved text.
    const auto again = cnclab::parse_experiment(loaded.resolved_yaml, "fuzz.yaml");
    if (again.resolved_yaml != loaded.resolved_yaml) {
      std::fprintf(stderr, "resolved YAML does not round-trip:\n%s\n---\n%s\n",
                   loaded.resolved_yaml.c_str(), again.resolved_yaml.c_str());
      std::abort();
    }
  } catch (const cnclab::ConfigError& e) {
    if (std::string(e.what()).find("fuzz.yaml") == std::string::npos) {
      std::fprintf(stderr, "ConfigError without location: %s\n", e.what());
      std::abort();
    }
  }
  return 0;
}
