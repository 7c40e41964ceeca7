#include "cnclab/deploy/training_dataset.hpp"

#include <iostream>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/progress.hpp"
#include "cnclab/data/dataset_cache.hpp"
#include "cnclab/data/dataset_file.hpp"
#include "cnclab/data/dataset_spec.hpp"

namespace cnclab {
namespace fs = std::filesystem;

Dataset training_dataset(const DeployedModel& m, const TrainingDataOptions& o) {
  std::error_code ec;
  if (!m.dataset_file.empty() && fs::is_regular_file(m.dataset_file, ec)) {
    try {
      Dataset d = read_dataset(m.dataset_file);
      if (d.content_hash() == m.dataset_hash) return d;
    } catch (const IoError&) {
      // Unreadable or replaced: made again below.
    }
  }
  const ConfigDocument doc = ConfigDocument::parse(m.resolved_yaml, m.result_file + ": /config");
  const DatasetSpec spec = read_dataset_spec(doc.root().section("dataset"));
  StagedProgress progress(
      "dataset " + spec.generator->name() + " (the training data of " + m.experiment + ")",
      o.log ? *o.log : std::cerr,
      {o.log ? ProgressMode::automatic : ProgressMode::quiet, 5.0, 0.1});
  const CachedDataset cached =
      obtain_dataset(spec, m.generator_seed, o.data_dir, o.log, false, progress.callback());
  if (cached.content_hash != m.dataset_hash) {
    throw Error(m.result_file + ": its training dataset made again (" + cached.path.string() +
                ") has content hash " + cached.content_hash + ", the result trained on " +
                m.dataset_hash + " (has the generator changed since?)");
  }
  return cached.dataset;
}

}  // namespace cnclab
