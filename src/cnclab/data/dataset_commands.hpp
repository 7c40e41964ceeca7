#pragma once
// `cnclab dataset generate` and `cnclab dataset show` (src/cli wires their
// arguments). Return the exit code; bad configuration
// throws ConfigError (exit 2), unreadable files IoError (exit 1).
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/core/progress.hpp"
#include "cnclab/data/dataset.hpp"

namespace cnclab {

// Reads the `dataset:` section of `config` ({generator, seed?, options};
// other top-level sections, e.g. an experiment's model and trainer, are
// ignored), generates the dataset and writes it atomically to `out_file`
// (default datasets/<config stem>.h5). The seed is dataset.seed, else the
// one an experiment derives from its top-level `seed` ("generator" stream),
// else 0. `dataset.targets` (when given) keeps those targets, as a run
// would. Nothing is written when anything fails. Prints one summary line on
// `out`; progress of a long generation goes to `err` (`progress` mode).
int dataset_generate_command(const std::filesystem::path& config,
                             const std::vector<std::string>& overrides,
                             const std::optional<std::filesystem::path>& out_file,
                             ProgressMode progress, std::ostream& out, std::ostream& err);

// Prints a dataset file: counts, input/target ranges with units, a text
// histogram of the first target, metadata ranges and, when a metadata column
// `convex` exists, the convex/concave split.
int dataset_show_command(const std::filesystem::path& file, std::ostream& out);

// The same report for a dataset in memory (`source` names it).
void print_dataset_summary(const Dataset& dataset, const std::string& source, std::ostream& out);

}  // namespace cnclab
