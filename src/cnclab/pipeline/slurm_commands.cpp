#include "cnclab/pipeline/slurm_commands.hpp"

#include <iomanip>

#include "cnclab/core/error.hpp"
#include "cnclab/pipeline/reproduce_inputs.hpp"
#include "cnclab/pipeline/reproduce_slurm.hpp"
#include "cnclab/pipeline/slurm_sweep_submit.hpp"
#include "cnclab/sweep/slurm_reproduce_record.hpp"

namespace cnclab {
namespace fs = std::filesystem;

int slurm_sweep_command(const fs::path& experiment, const std::vector<std::string>& words,
                        std::optional<std::uint64_t> seed, const SweepCommandOptions& o,
                        const SlurmOptions& slurm, std::ostream& out, std::ostream& log) {
  slurm.validate();
  if (!o.shard.empty()) throw ConfigError("--shard with --slurm: the array tasks are the shards");
  if (o.jobs != 0) {
    throw ConfigError("--jobs with --slurm: a task runs --cpus-per-task trials at once");
  }
  if (!o.trial_ids.empty()) throw ConfigError("--trial-ids with --slurm: the tasks set it");
  if (o.rerun) {
    throw ConfigError(
        "--rerun with --slurm: an array gets only the trials without a result; train them "
        "again with `cnclab sweep ... --rerun` (one job, or --shard K/N per job)");
  }
  if (!slurm.dry_run) check_slurm_clients();
  const SweepSlurmResult r = submit_sweep_slurm(experiment, words, seed, o, slurm, {}, out, log);
  return r.final_rejected ? 1 : 0;
}

int reproduce_slurm_command(const std::vector<std::string>& paths, const CommandOptions& options,
                            const SlurmOptions& slurm, std::ostream& out, std::ostream& log) {
  slurm.validate();
  if (options.jobs != 0) {
    throw ConfigError("--jobs with --slurm: each job runs on --cpus-per-task cores");
  }
  if (!slurm.dry_run) check_slurm_clients();
  for (const fs::path& p : {fs::current_path(), fs::absolute(options.results_dir)}) {
    if (p.string().find_first_of(" \t\n%") != std::string::npos) {
      throw ConfigError(p.string() +
                        ": a path with spaces or '%' cannot go on an #SBATCH line; choose "
                        "another --out or working folder");
    }
  }
  const ReproduceInputs inputs = reproduce_inputs(paths, options.profile);
  if (!inputs.profile_note.empty()) log << "note: " << inputs.profile_note << "\n";
  if (slurm.dry_run) out << "# dry run: nothing written or submitted\n";
  const ReproduceSlurmRun run = submit_reproduce_slurm(inputs, options, slurm, out, log);
  out << "\n== cnclab reproduce --slurm" << (slurm.dry_run ? " (dry run)" : "") << ": "
      << run.rows.size() << " experiment(s) and job(s) ==\n";
  for (const auto& r : run.rows) {
    out << std::left << std::setw(28) << r.name << " " << std::setw(12) << r.action << " ";
    if (!r.job.empty()) out << "job " << r.job << (r.after.empty() ? "" : " after " + r.after);
    out << (r.job.empty() ? "" : "; ") << r.why << "\n";
  }
  if (!slurm.dry_run && run.submitted > 0) {
    out << "jobs recorded in " << (reproduce_slurm_dir(options.results_dir) / "jobs.yaml").string()
        << "; run the same command again to submit what is missing or failed\n";
  }
  return run.exit_code;
}

}  // namespace cnclab
