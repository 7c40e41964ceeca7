#include "cli/reproduce_slurm.hpp"

#include <iomanip>

#include "cli/commands.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/pipeline/reproduce_slurm.hpp"
#include "cnclab/pipeline/slurm_sweep_submit.hpp"
#include "cnclab/sweep/slurm_queue.hpp"
#include "cnclab/sweep/slurm_reproduce_record.hpp"

namespace cnclab {
namespace fs = std::filesystem;

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

int reproduce_status_command(const fs::path& results_dir, std::ostream& out) {
  const ReproduceRecord record = read_reproduce_record(results_dir);
  SlurmTaskStates jobs;
  std::string note;
  try {
    jobs = squeue_jobs();
  } catch (const Error& e) {
    note = e.what();
  }
  out << "reproduce --slurm jobs of " << results_dir.string() << ": " << record.size() << "\n";
  for (const auto& [file, e] : record) {
    const auto state = jobs.find(e.job);
    std::error_code ec;
    // A result file, or a sweep folder with its summary.
    const bool made = !e.output.empty() && (fs::is_regular_file(e.output, ec) ||
                                            fs::exists(fs::path(e.output) / "summary.h5", ec));
    out << "  " << std::left << std::setw(28) << e.name << " job " << e.job << " "
        << (state == jobs.end() ? "(ended or unknown to Slurm)" : state->second)
        << (made ? ", output present" : "") << (e.array.empty() ? "" : "; array " + e.array)
        << "\n";
  }
  if (!note.empty()) out << "  note: " << note << "\n";
  return 0;
}

}  // namespace cnclab
