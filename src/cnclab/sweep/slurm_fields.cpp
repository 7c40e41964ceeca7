#include "cnclab/sweep/slurm_fields.hpp"

#include <algorithm>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/sweep/sweep_job.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// sbatch splits #SBATCH lines at whitespace: one word, no quotes.
Rule slurm_word_rule() {
  return Rule::matches("[^ \t\n'\"]*", "must be one word (no spaces or quotes)");
}

// Reads the block of one loaded document over `o`; every other key is the
// experiment's or the sweep file's reader's to check.
void read_block_of(const fs::path& file, const std::string& profile, SlurmOptions& o) {
  ConfigDocument doc = ConfigDocument::load(file, profile);
  const ConfigReader root = doc.root();
  for (const auto& key : root.keys()) {
    if (key != "slurm") root.raw(key);
  }
  if (!root.has("slurm")) return;
  const ConfigReader block = root.section("slurm");
  slurm_fields().read(block, o);
  doc.check_all_consumed();  // an unknown key of the block
  block.validate([&] { slurm_fields().check(o); });
  try {
    o.validate();  // the signal's seconds range
  } catch (const ConfigError& e) {
    root.fail("slurm", e.what());
  }
}

}  // namespace

const FieldList<SlurmOptions>& slurm_fields() {
  using S = SlurmOptions;
  static const auto fields =
      FieldList<S>()
          .field("partition", &S::partition, "#SBATCH --partition ('': the cluster's default)",
                 slurm_word_rule())
          .field("time", &S::time,
                 "#SBATCH --time per job or array task, e.g. 02:00:00 or 1-00:00:00 ('': the "
                 "partition's default)",
                 slurm_word_rule())
          .field("cpus_per_task", &S::cpus_per_task,
                 "#SBATCH --cpus-per-task; also the trials an array task runs at once",
                 Rule::at_least(1))
          .field("mem", &S::mem, "#SBATCH --mem per job or task, e.g. 4G ('': the default)",
                 slurm_word_rule())
          .field("max_concurrent", &S::max_concurrent,
                 "array tasks running at once (the %K throttle); 0: no limit")
          .field("tasks", &S::tasks,
                 "array tasks, trials dealt round-robin; 0: one per trial to run",
                 Rule::in(0, true, static_cast<double>(kMaxArrayTasks), true))
          .field("signal", &S::signal,
                 "warning SIG@SECONDS before a kill (#SBATCH --signal=B:...), SIG USR1 or USR2, "
                 "SECONDS 10..65535",
                 Rule::matches("(USR1|USR2)@[0-9]{2,5}", "must be SIG@SECONDS, e.g. USR1@120"));
  return fields;
}

FieldInfo slurm_block_info() {
  FieldInfo i = custom_info("slurm",
                            "defaults of `--slurm`'s options (flags given win); ignored by local "
                            "runs and never part of a result's identity (README: Slurm)",
                            FieldKind::section);
  i.optional = true;
  i.children = slurm_fields().info();
  return i;
}

void read_slurm_block(const fs::path& file, const std::string& profile, SlurmOptions& options) {
  if (experiment_kind(file) == "sweep") {
    read_block_of(load_sweep_job(file, {}, profile).experiment, profile, options);
  }
  read_block_of(file, profile, options);
}

SlurmOptions resolve_slurm_options(const SlurmOptions& command_line, const fs::path& file,
                                   const std::string& profile) {
  SlurmOptions o;
  read_slurm_block(file, profile, o);
  // The given flags through the same declarations: one copy per key.
  const YAML::Node given_values = slurm_fields().to_node(command_line);
  YAML::Node given(YAML::NodeType::Map);
  for (const auto& key : command_line.given) given[key] = given_values[key];
  const ConfigDocument doc = ConfigDocument::parse(YAML::Dump(given), "the command line");
  slurm_fields().read(doc.root(), o);
  o.given = command_line.given;
  o.dry_run = command_line.dry_run;
  return o;
}

}  // namespace cnclab
