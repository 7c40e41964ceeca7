#include "cli/cli_wiring.hpp"

#include <algorithm>
#include <iostream>

#include "cnclab/core/rng.hpp"
#include "cnclab/experiment/result_store.hpp"

namespace cnclab {

namespace {

// The results-folder rule (result_store.hpp results_folder), said the same
// way by every command that reads or writes results.
const char* const kProfileHelp =
    "Apply the experiment files' `profiles: {NAME: ...}` overrides (e.g. quick); results are "
    "then in ROOT/NAME (ROOT: --out or --results, default results)";

}  // namespace

const char* const kResultsRootHelp =
    "Results root ROOT: results are in ROOT, or ROOT/NAME with --profile NAME (a ROOT that "
    "holds results directly and no NAME/ folder, the layout before, is used as it is)";

const CLI::Validator& count_validator() {
  static const CLI::Validator count(
      [](std::string& text) {
        const bool digits = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
          return c >= '0' && c <= '9';
        });
        return digits ? std::string() : "expected a non-negative integer, got " + text;
      },
      "");
  return count;
}

std::optional<std::uint64_t> seed_option(const std::optional<std::string>& text,
                                         const char* option) {
  if (!text) return std::nullopt;
  return parse_seed(*text, option);
}

void apply_profile_dir(const CLI::App& sub, const char* option, const std::string& profile,
                       std::filesystem::path& dir) {
  const ResultsFolder folder = results_folder(dir, profile, sub.get_option(option)->count() > 0);
  if (!folder.note.empty()) std::cerr << "cnclab: note: " << folder.note << "\n";
  dir = folder.dir;
}

void add_store_options(CLI::App& sub, std::filesystem::path& results_dir,
                       std::filesystem::path& datasets_dir) {
  sub.add_option("--out", results_dir, kResultsRootHelp)->capture_default_str();
  sub.add_option("--data-dir", datasets_dir, "Dataset cache folder")->capture_default_str();
}

void add_quiet_flag(CLI::App& sub, bool& quiet) {
  sub.add_flag("--quiet,-q", quiet, "No progress output");
}

void add_profile_option(CLI::App& sub, std::string& profile) {
  sub.add_option("--profile", profile, kProfileHelp);
}

void add_seed_option(CLI::App& sub, std::optional<std::string>& seed_text) {
  sub.add_option("--seed", seed_text, "Master seed (overrides the YAML's seed)")->type_name("UINT");
}

}  // namespace cnclab
