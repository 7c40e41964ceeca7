#pragma once
// "Did you mean" for misspelt names: keys, enumerated values (metrics,
// activations, generators, trainers).
#include <cstddef>
#include <string>
#include <vector>

namespace cnclab {

// Optimal string alignment distance: insertions, deletions, substitutions
// and transpositions of neighbours ("rsme" is 1 from "rmse"), each 1.
std::size_t edit_distance(const std::string& a, const std::string& b);

// The closest of `names` to `word` when it is a near miss (edit distance at
// most 2; the first of equals), else "".
std::string closest_name(const std::string& word, const std::vector<std::string>& names);

// " (did you mean 'x'?)" for closest_name, else "".
std::string did_you_mean(const std::string& word, const std::vector<std::string>& names);

}  // namespace cnclab
