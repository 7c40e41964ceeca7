#include "cli/cli_wiring.hpp"

#include <algorithm>

#include "cnclab/core/rng.hpp"

namespace cnclab {

const char* const kProfileHelp =
    "Apply the experiment files' `profiles: {NAME: ...}` overrides (e.g. quick); results then "
    "default to <results>/NAME";

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
  if (!profile.empty() && sub.get_option(option)->count() == 0) dir = dir / profile;
}

}  // namespace cnclab
