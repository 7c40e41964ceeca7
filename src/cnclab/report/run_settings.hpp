#pragma once
// What a table's runs actually ran with, read from their result files'
// resolved configs (profile applied), never from a manifest's description of
// what they were meant to be: a quick profile that swaps in another trainer
// shows in the note under the table, not only in `--format json`.
#include <string>
#include <vector>

namespace cnclab {

// The settings of `resolved_yamls` (each a result's /config) at the dotted
// `keys`, grouped by their first segment, in the order given:
//   "trainer: type NAME, batch_size 32, epochs 5; model: dropout.keep_probability 0.3 to 0.9 (7
//   values)"
// A key whose value differs between the runs lists its values ("200 or
// 2000"; numbers sorted, more than three as a range); a key no run has is
// left out, one some runs lack shows "(absent)" among its values.
std::string run_settings(const std::vector<std::string>& resolved_yamls,
                         const std::vector<std::string>& keys);

// "ran with profile quick" / "ran with no profile", then " (per the result
// files' configs): " and run_settings(...): a table's note on its runs.
std::string ran_with(const std::string& profile, const std::vector<std::string>& resolved_yamls,
                     const std::vector<std::string>& keys);

}  // namespace cnclab
