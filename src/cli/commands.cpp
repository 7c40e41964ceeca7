#include "cli/commands.hpp"

#include <cstdlib>

#include "cnclab/core/config_abbreviate.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/isa.hpp"
#include "cnclab/core/share_paths.hpp"
#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/experiment/profiles.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/runner.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/io/provenance.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/pipeline/run_options.hpp"
#include "cnclab/report/sweep_report.hpp"
#include "cnclab/studies/five_axis/trochoid_job.hpp"

namespace cnclab {
namespace fs = std::filesystem;

namespace {

// The job kind of a `kind: <job>` file with its context (--seed becomes the
// override seed=N: a job without a seed key rejects it), or nullopt for a
// training experiment.
std::optional<std::pair<JobKind, JobContext>> job_of(const fs::path& experiment,
                                                     const std::vector<std::string>& overrides,
                                                     std::optional<std::uint64_t> seed,
                                                     const CommandOptions& options,
                                                     std::ostream* log) {
  auto kind = find_job_kind(experiment_kind(experiment));
  if (!kind) return std::nullopt;
  JobContext context{options, overrides, options.quiet ? nullptr : log};
  if (seed) context.overrides.push_back("seed=" + std::to_string(*seed));
  return std::pair{std::move(*kind), std::move(context)};
}

// `validate`'s resolved config, large arrays abbreviated unless --full (then
// it is the config as it is, usable as an experiment file).
void print_config_text(const std::string& resolved, const CommandOptions& options,
                       std::ostream& out) {
  const AbbreviatedConfig shown =
      options.full ? AbbreviatedConfig{resolved, 0} : abbreviate_config(resolved);
  if (shown.abbreviated > 0) {
    out << "# " << shown.abbreviated << " array(s) of more than " << kAbbreviateScalars
        << " numbers shown as shape and hash; --full prints them\n";
  }
  out << shown.text;
}

}  // namespace

int run_command(const fs::path& experiment, const std::vector<std::string>& overrides,
                std::optional<std::uint64_t> seed, const CommandOptions& options, std::ostream& out,
                std::ostream& log) {
  check_profile(experiment, options.profile);
  if (const auto job = job_of(experiment, overrides, seed, options, &log)) {
    clean_stale_partials({options.results_dir, options.datasets_dir}, log);
    const JobReport report = job->first.run(experiment, job->second);
    if (!options.quiet && !report.report.empty()) out << report.report << "\n";
    out << report.name << ": " << report.action << " (" << report.why << ")";
    if (!report.detail.empty()) out << "; " << report.detail;
    out << "\n";
    if (!report.file.empty()) out << report.file << "\n";
    return 0;
  }
  const LoadedExperiment loaded = load_experiment(experiment, overrides, seed, options.profile);
  for (const auto& note : loaded.notes) log << "note: " << note << "\n";
  clean_stale_partials({options.results_dir, options.datasets_dir}, log);
  const RunOutcome outcome = run_experiment(loaded, run_options(options, log));
  if (!outcome.ok && loaded.spec.may_diverge) {
    out << loaded.spec.name << ": " << outcome.message << " (allowed: may_diverge)\n"
        << outcome.result_file.string() << "\n";
    return 0;
  }
  if (!outcome.ok) {
    out << "FAILED " << loaded.spec.name << ": " << outcome.message << "\n"
        << "result (status failed): " << outcome.result_file.string() << "\n";
    return 1;
  }
  if (!options.quiet) out << loaded.spec.name << ": " << metrics_line(outcome.metrics) << "\n";
  for (const auto& w : outcome.warnings)
    log << "warning: " << loaded.spec.name << ": " << w << "\n";
  for (const auto& n : outcome.notes) log << "note: " << loaded.spec.name << ": " << n << "\n";
  out << outcome.result_file.string() << "\n";
  return 0;
}

int validate_command(const fs::path& experiment, const std::vector<std::string>& overrides,
                     std::optional<std::uint64_t> seed, const CommandOptions& options,
                     std::ostream& out) {
  check_profile(experiment, options.profile);
  if (const auto job = job_of(experiment, overrides, seed, options, nullptr)) {
    // Resolved before anything is printed: an invalid file prints no "valid".
    const std::string resolved = job->first.resolved_yaml(experiment, job->second);
    out << "# " << experiment.string() << ": valid; resolved configuration:\n";
    print_config_text(resolved, options, out);
    return 0;
  }
  const LoadedExperiment loaded = load_experiment(experiment, overrides, seed, options.profile);
  out << "# " << experiment.string() << ": valid; resolved configuration:\n";
  for (const auto& note : loaded.notes) out << "# note: " << note << "\n";
  print_config_text(loaded.resolved_yaml, options, out);
  return 0;
}

int show_command(const std::vector<std::string>& result_files, const CommandOptions& options,
                 std::ostream& out) {
  ShowOptions show;
  show.full_config = options.full;
  for (std::size_t i = 0; i < result_files.size(); ++i) {
    if (i) out << "\n";
    if (is_sweep_summary(result_files[i])) {
      print_stored_summary(result_files[i], out);
    } else {
      print_result(read_result(result_files[i]), out, show);
    }
  }
  return 0;
}

int gcode_command(const std::string& toolpath, const fs::path& config, const fs::path& output,
                  const std::vector<std::string>& overrides, std::ostream& out) {
  if (toolpath != "trochoid") {
    throw ConfigError("gcode: unknown tool path '" + toolpath + "'; known: trochoid");
  }
  const TrochoidOutcome outcome = run_trochoid_job(load_trochoid_job(config, overrides));
  write_text_atomically(output, outcome.program.text);
  out << outcome.report << "\nG-code written to " << output.string() << "\n";
  return 0;
}

int version_command(std::ostream& out) {
  const Provenance p = make_provenance(0);
  out << "cnclab " << p.cnclab_version << " (git " << p.git_commit << ")\n";
  // The hot kernels' instruction-set level (core/isa.hpp; CNCLAB_ISA forces one).
  const char* forced = std::getenv("CNCLAB_ISA");
  std::string compiled;
  for (const IsaLevel l : compiled_isa_levels())
    compiled += (compiled.empty() ? "" : ", ") + std::string(to_string(l));
  out << "kernels: " << describe(active_isa())
      << (forced && *forced ? ", set by CNCLAB_ISA" : ", the widest this CPU supports")
      << " (compiled: " << compiled << ")\n";
  for (const auto& [name, version] : p.libraries) out << "  " << name << " " << version << "\n";
  // Where shared configs, experiments and reference numbers come from
  // after the project's own (core/share_paths.hpp).
  const ShareRoots share = installed_share_roots();
  out << "shared files:";
  if (share.roots.empty()) out << " " << share.none_note();
  out << "\n";
  for (const auto& root : share.roots)
    out << "  " << root.dir.string() << " (" << root.why << ")\n";
  return 0;
}

}  // namespace cnclab
