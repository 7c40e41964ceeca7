#pragma once
// Training stages of NARX networks, kept so that runs sharing a stage train
// it once.
//
// A stage's outcome is a deterministic function of the network's shape, the
// stage's resolved options, the training series, the starting weights and
// the program that trains (its executable, and the instruction-set level its
// kernels run at, core/isa.hpp). The studies repeat stages: seed 002's
// training methods start two_stage, two_stage_retry and open_loop_only from
// the same open-loop stage per seed, and two_stage_retry repeats two_stage's
// closed-loop stage up to its second try. The first run of a stage writes
// its weights and record to
//
//   <dir>/<16 hex digits>.h5   (dir: RunOptions::datasets_dir/narx-stages)
//
// the hash covering all of the above (FNV-1a, core/hash.hpp); a later run
// with the same key reads them instead of training. Exact: the weights are
// the doubles the stage ended with, so the run continues bit for bit as if
// it had trained the stage (only the record's wall times are those of the
// run that trained it). A rebuilt executable has other keys, so a change to
// the training code never meets a stage it did not train. Files are written
// atomically (io/atomic_file.hpp); two runs training the same stage at once
// both train it and write the same file. `cnclab gc` lists the folder (it
// is a cache: removing it costs only the training time).
#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cnclab/experiment/narx_spec.hpp"
#include "cnclab/nn/narx.hpp"
#include "cnclab/train/summary.hpp"

namespace cnclab {

// A stage as it ended: its record and the weights after it.
struct CachedNarxStage {
  Summary summary;
  Eigen::VectorXd params;
};

class NarxStageCache {
 public:
  // A cache in `dir` (created when a stage is stored). The executable's
  // identity is read here; when it cannot be read (no /proc/self/exe), the
  // cache is off: it never finds and never stores.
  explicit NarxStageCache(std::filesystem::path dir);

  bool enabled() const { return !program_.empty(); }
  const std::filesystem::path& dir() const { return dir_; }

  // The key of `stage` of a network `narx` trained on inputs v (one column
  // per channel) and targets e, sequences starting at `starts`, from `start`.
  std::string key(const NarxOptions& narx, const TrainingStage& stage, const Eigen::MatrixXd& v,
                  const Eigen::VectorXd& e, const std::vector<Eigen::Index>& starts,
                  const Eigen::VectorXd& start) const;

  // The stage stored under `key`; nullopt when there is none or it does not
  // read back whole (a foreign or damaged file is trained again, and
  // replaced; it is read first in a child process, io/isolated_read.hpp).
  std::optional<CachedNarxStage> find(const std::string& key) const;

  // Stores a stage's outcome under `key`. A cache that cannot be written
  // (read-only folder, full disk) costs only time: the error is dropped.
  void store(const std::string& key, const CachedNarxStage& stage) const;

 private:
  std::filesystem::path dir_;
  std::string program_;  // the executable's content hash and the ISA level; "" = off
};

}  // namespace cnclab
