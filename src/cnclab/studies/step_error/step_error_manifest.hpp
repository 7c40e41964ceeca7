#pragma once
// The step-error study's manifest (configs/studies/step_error_tables.yaml):
// which experiment file made each number of seed 000's Tables 2-7, per
// variant ("paper": the paper's hyperparameters; optionally "tuned"), and the
// keep/refit normaliser pair at 15 % fine-tuning. Paths in the manifest are
// relative to it; they are returned resolved.
//
//   variants:
//     paper:
//       table2: {0.3: ../../experiments/step_error/table2_keep_0.3.yaml, ...}
//       surface1: ...            # Table 3, Figs. 5-6
//       surface1_no_dropout: ... # Fig. 6b
//       surface2: {0: ..., 1: ..., 5: ..., 10: ..., 15: ...}   # fine-tune % -> file
//       surface3: {0: ..., ...}
//       note: "one line: what this variant is meant to be" (the tables add what
//                                it ran with, from the result files)
//     tuned: {...}               # optional, same keys
//   normaliser:
//     default: refit             # or keep
//     keep: {surface2: FILE, surface3: FILE}
//     refit: {surface2: FILE, surface3: FILE}
//   repeats:                     # optional: seed-to-seed spread (step_error_repeats.hpp)
//     variant: tuned             # the variant whose headline rows are repeated
//     table2: FILE               # kind: sweep over model.dropout.keep_probability (Table 2's
//                                # p and 1.0) with a validation split to choose p on
//     surface1: FILE             # kind: sweep of surface 1 itself (keep 1.0, 70/30 split)
//     surface2_ft15: FILE        # kind: sweep over init_from (refit and keep chains)
//     surface3_ft15: FILE
//   targets: [...]                 # `--check` (report/targets.hpp; names: step_error_measures.hpp)
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cnclab {

struct StudyVariant {
  std::string name;  // "paper", "tuned", ...
  std::string note;
  std::map<double, std::filesystem::path> table2;  // keep probability p -> experiment
  std::filesystem::path surface1, surface1_no_dropout;
  std::map<double, std::filesystem::path> surface2, surface3;  // fine-tune % -> experiment
};

struct NormaliserChoice {
  std::string name;  // "keep" or "refit"
  std::filesystem::path surface2, surface3;
};

// The `kind: sweep` files that repeat a variant's headline rows over seeds
// (sweep repeats): Table 2's keep probabilities (and none), surface 1, and
// the 15 % fine-tunings with the normaliser refitted and kept.
struct StudyRepeats {
  std::string variant;  // a variant of `variants`
  std::filesystem::path table2, surface1, surface2_ft15, surface3_ft15;
};

struct StudyManifest {
  std::vector<StudyVariant> variants;        // file order; "paper" first
  std::string normaliser_default;            // "keep" or "refit"
  std::vector<NormaliserChoice> normaliser;  // keep, refit
  std::optional<StudyRepeats> repeats;
};

// Throws MissingResults when the file is absent (the study is not set up),
// ConfigError for anything malformed (unknown keys included).
StudyManifest read_step_error_manifest(const std::filesystem::path& file);

}  // namespace cnclab
