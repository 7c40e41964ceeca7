#pragma once
// The runs below some folders, with what listing them needs (cnclab runs,
// gc, report), kept in an index file so that listing thousands of results
// does not read them all:
//
//   <results root>/.runs-index.json
//     {"format": "cnclab-runs-index", "version": 1,
//      "runs": [{"file", "size", "mtime_ns", "error" | run fields ...}]}
//
// The index is never trusted over the files: every listing walks the
// folders, and a file whose size or modification time differs from its
// entry (or that has none) is read again; entries of files that are gone
// are dropped. A missing, unreadable or foreign index is rebuilt. It is
// written atomically, and a folder that cannot be written only costs speed.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "cnclab/experiment/result_summary.hpp"

namespace cnclab {

struct IndexedRun {
  std::filesystem::path file;  // absolute, lexically normal
  std::uintmax_t size = 0;
  std::int64_t mtime_ns = 0;
  std::string error;      // not a readable result: why (summary and config unset)
  ResultSummary summary;  // resolved_yaml left empty: `config` holds it
  // The resolved config as dotted keys, arrays abbreviated (flatten_config,
  // compare.hpp).
  std::vector<std::pair<std::string, std::string>> config;
};

struct RunScan {
  std::vector<IndexedRun> runs;        // readable results, sorted by file
  std::vector<IndexedRun> unreadable;  // *.h5 files that are not results (error set)
  std::size_t read = 0;                // files read this time
  std::size_t reused = 0;              // entries taken from the index
  std::filesystem::path index_file;
  std::string index_note;  // why the index was rebuilt or not written ("" when fine)
};

// Every result file below `inputs` (folders, recursively, or files): *.h5
// but partial temporaries (atomic_file.hpp) and sweep summaries (summary.h5).
// `index_file` empty: no index.
RunScan scan_runs(const std::vector<std::filesystem::path>& inputs,
                  const std::filesystem::path& index_file);

// The index of the results root: <results_dir>/.runs-index.json.
std::filesystem::path runs_index_path(const std::filesystem::path& results_dir);

}  // namespace cnclab
