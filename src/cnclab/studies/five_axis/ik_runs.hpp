#pragma once
// The IK networks `cnclab tables ik` compares, one per axis X, Y, Z, A, C,
// in three variants:
//   sgdm     experiments/ik/ik_<axis>.yaml            seed 004 Table 5's settings (required)
//   search   experiments/ik_search/search_<axis>.yaml the trial a `kind: sweep` job selected
//                                                     by validation MSE (sweep_job.hpp)
//   trainbr  experiments/ik_trainbr/ik_<axis>.yaml    the same networks trained with trainbr
// A missing search or trainbr result leaves that axis empty with a note.
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cnclab/experiment/run_record.hpp"
#include "cnclab/experiment/spec.hpp"
#include "cnclab/report/tables.hpp"

namespace cnclab {

inline constexpr std::array<const char*, 5> kIkAxes = {"X", "Y", "Z", "A", "C"};

struct IkAxisRun {
  std::string axis;
  std::filesystem::path source;  // experiment file, or the sweep trial's result file
  LoadedExperiment loaded;
  std::filesystem::path result_file;  // the result read
  std::filesystem::path selection;    // search only: the job's selection result that named it
  RunRecord record;
};

struct IkVariant {
  std::string key;    // sgdm | search | trainbr
  std::string label;  // column label: ours | search | trainbr
  std::array<std::optional<IkAxisRun>, 5> axes;
  std::vector<std::string> notes;  // why axes are missing; what the search selected from
  bool any() const;
};

// sgdm first, then search and trainbr, found through the result store
// (experiment/result_store.hpp). Throws MissingResults when an sgdm result is
// missing, Error when a result is for another target or failed.
std::vector<IkVariant> load_ik_variants(const TablesOptions& options);

// The variants' experiment and job files that exist: TableEntry::experiment_files.
std::vector<std::filesystem::path> ik_experiment_files(const TablesOptions& options);

}  // namespace cnclab
