#pragma once
// What every command and job is given: results and dataset folders, quiet,
// force, regenerate, profile, parallel jobs (set by src/cli).
#include <cstddef>
#include <filesystem>
#include <string>

namespace cnclab {

struct CommandOptions {
  std::filesystem::path results_dir = "results";
  std::filesystem::path datasets_dir = "datasets";
  bool quiet = false;
  bool regenerate = false;  // --regenerate: generate datasets even when cached
  bool force = false;       // reproduce --force: run even when the result is current
  // --profile NAME: the experiment files' `profiles: {NAME: ...}` overrides
  // (core/config.hpp); `reproduce --quick` is --profile quick.
  std::string profile;
  // reproduce --jobs N: experiments trained at once, each in its own process
  // (0 = the cores this process may use).
  std::size_t jobs = 0;
  // validate/show --full: configs with every array in full (else arrays of
  // more than kAbbreviateScalars numbers print as shape and hash,
  // core/config_abbreviate.hpp).
  bool full = false;
  // reproduce --check: check the declared targets of every table printed
  // (report/targets.hpp); a FAIL makes the exit code 1.
  bool check = false;
};

}  // namespace cnclab
