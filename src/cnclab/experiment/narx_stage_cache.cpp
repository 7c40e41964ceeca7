#include "cnclab/experiment/narx_stage_cache.hpp"

#include <yaml-cpp/yaml.h>

#include "cnclab/core/error.hpp"
#include "cnclab/core/hash.hpp"
#include "cnclab/core/isa.hpp"
#include "cnclab/experiment/result_layout.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/io/file_format.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/io/isolated_read.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

constexpr const char* kStageFormat = "cnclab-narx-stage";
constexpr int kStageFormatVersion = 1;

void add_matrix(Hasher& h, const Eigen::MatrixXd& m) {
  h.add(static_cast<std::uint64_t>(m.rows())).add(static_cast<std::uint64_t>(m.cols()));
  h.add(std::span<const double>(m.data(), static_cast<std::size_t>(m.size())));
}

}  // namespace

NarxStageCache::NarxStageCache(fs::path dir) : dir_(std::move(dir)) {
  // The running executable's content: a rebuilt program has other keys.
  if (const std::optional<std::string> exe = file_hash_hex("/proc/self/exe")) {
    program_ = *exe + " " + to_string(active_isa());
  }
}

std::string NarxStageCache::key(const NarxOptions& narx, const TrainingStage& stage,
                                const Eigen::MatrixXd& v, const Eigen::VectorXd& e,
                                const std::vector<Eigen::Index>& starts,
                                const Eigen::VectorXd& start) const {
  Hasher h;
  h.add(std::string_view(kStageFormat)).add(static_cast<std::uint64_t>(kStageFormatVersion));
  h.add(std::string_view(program_));
  for (const std::size_t n : {narx.input_delays, narx.feedback_delays, narx.hidden,
                              narx.first_input_delay, narx.inputs}) {
    h.add(static_cast<std::uint64_t>(n));
  }
  h.add(std::string_view(to_string(narx.hidden_activation)));
  // The stage as its resolved flow map (every trainer option, the horizon).
  // fallback_horizon is left out: a second try is a stage of its own, run
  // after this one, so a stage with and one without it train alike.
  TrainingStage trained = stage;
  trained.fallback_horizon = 0;
  YAML::Emitter text;
  text << stages_to_node({trained});
  h.add(std::string_view(text.c_str()));
  add_matrix(h, v);
  add_matrix(h, e);
  h.add(static_cast<std::uint64_t>(starts.size()));
  for (const Eigen::Index s : starts) h.add(static_cast<std::uint64_t>(s));
  add_matrix(h, start);
  return h.hex();
}

std::optional<CachedNarxStage> NarxStageCache::find(const std::string& key) const {
  const fs::path file = dir_ / (key + ".h5");
  std::error_code ec;
  if (!enabled() || !fs::is_regular_file(file, ec)) return std::nullopt;
  const auto read = [&] {
    const H5File f = H5File::open_read(file);
    require_format(f, kStageFormat, kStageFormatVersion);
    if (f.attribute_string("/", "key") != key) throw IoError(file.string() + ": another key");
    NarxStageRecord record;
    ResultLayoutReader io(f);
    result_layout::narx_stage(io, "/stage", record);
    CachedNarxStage stage{std::move(record.summary), {}};
    const std::vector<double> params = f.read_vector("/stage/parameters");
    stage.params =
        Eigen::Map<const Eigen::VectorXd>(params.data(), static_cast<Eigen::Index>(params.size()));
    return stage;
  };
  try {
    // As every HDF5 file cnclab reads: first in a child (io/isolated_read.hpp).
    probe_in_child(file, [&] { (void)read(); });
    return read();
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

void NarxStageCache::store(const std::string& key, const CachedNarxStage& stage) const {
  if (!enabled()) return;
  try {
    AtomicOutput out(dir_ / (key + ".h5"));
    H5File f = H5File::create(out.temp_path());
    write_format(f, kStageFormat, kStageFormatVersion);
    f.set_attribute("/", "key", key);
    f.set_attribute("/", "program", program_);
    NarxStageRecord record;
    record.summary = stage.summary;
    ResultLayoutWriter io(f);
    result_layout::narx_stage(io, "/stage", record);
    f.write_vector(
        "/stage/parameters",
        std::span<const double>(stage.params.data(), static_cast<std::size_t>(stage.params.size())),
        "1");
    mark_complete(f);
    f.close();
    out.commit();
  } catch (const std::exception&) {
    // A cache that cannot be written costs only time (header).
  }
}

}  // namespace cnclab
