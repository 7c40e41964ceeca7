// Fuzz target: one command-line override `key=value`, parsed and applied to
// an experiment. Contract: success, or ConfigError naming the override.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "cnclab/core/error.hpp"
#include "cnclab/core/override.hpp"
#include "cnclab/experiment/spec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const cnclab::Override o = cnclab::parse_override(text);
    if (o.path.empty()) std::abort();
  } catch (const cnclab::ConfigError& e) {
    if (std::string(e.what()).find("override '") == std::string::npos) {
      std::fprintf(stderr, "ConfigError without the override text: %s\n", e.what());
      std::abort();
    }
    return 0;
  }
  try {
    cnclab::parse_experiment(
        "name: f\nseed: 1\ndataset: {generator: friedman1}\nmodel: {}\ntrainer: {type: sgdm}\n",
        "fuzz.yaml", {text});
  } catch (const cnclab::ConfigError& e) {
    const std::string msg = e.what();
    if (msg.find("fuzz.yaml") == std::string::npos && msg.find("override") == std::string::npos) {
      std::fprintf(stderr, "ConfigError without location: %s\n", e.what());
      std::abort();
    }
  }
  return 0;
}
