#pragma once
// Configs printed for people (`cnclab validate`, `cnclab show`): an array of
// more than kAbbreviateScalars numbers (an inlined NURBS surface's control
// points, knot vectors) would bury the settings, so it prints as its shape
// and a short hash instead:
//   control_points: 16 × 16 × 3, hash 1a2b3c4d
//   knots_u: 20 values, hash 5e6f7a8b
// An array is a sequence whose items are scalars or arrays themselves; its
// size is the number of scalars in it, nested ones included. The shape is
// the lengths down the nesting when every level is regular, else "N items,
// M values". The hash: the first 8 hex digits of hash_hex (FNV-1a, hash.hpp)
// of its flow YAML text, so equal arrays show equal hashes. Sequences of maps
// (trainer.stages) are not arrays: their maps are abbreviated inside.
// `--full` prints the config as it is.
#include <cstddef>
#include <string>

namespace cnclab {

inline constexpr std::size_t kAbbreviateScalars = 16;

struct AbbreviatedConfig {
  std::string text;             // the config text with large arrays abbreviated
  std::size_t abbreviated = 0;  // how many arrays were; 0: `text` is the input unchanged
};

// `yaml_text` unchanged when no array has more than `max_scalars` scalars;
// else re-emitted (block style, arrays in their own style) with each such
// array replaced by its summary. Text that is not valid YAML is returned as is.
AbbreviatedConfig abbreviate_config(const std::string& yaml_text,
                                    std::size_t max_scalars = kAbbreviateScalars);

}  // namespace cnclab
