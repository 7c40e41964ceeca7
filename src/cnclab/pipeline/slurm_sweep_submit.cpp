#include "cnclab/pipeline/slurm_sweep_submit.hpp"

#include <algorithm>

#include "cnclab/core/error.hpp"
#include "cnclab/experiment/result_store.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/pipeline/slurm_queue_view.hpp"
#include "cnclab/sweep/slurm_fields.hpp"
#include "cnclab/sweep/slurm_tools.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// "12345" or "12345;cluster" (sbatch --parsable) -> "12345".
std::string parsed_job_id(const ToolRun& r) {
  std::string id = r.out.substr(0, r.out.find_first_of(";\n"));
  if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos) {
    throw Error("sbatch printed no job id (output '" + r.out + "')");
  }
  return id;
}

std::string tool_message(const ToolRun& r) {
  std::string m = r.err.empty() ? r.out : r.err;
  while (!m.empty() && (m.back() == '\n' || m.back() == ' ')) m.pop_back();
  return m;
}

// `cnclab sweep ...` as an array task runs it: the same sweep into the same
// folder, every path as this process resolved it.
std::vector<std::string> array_task_command(const std::string& cnclab, const fs::path& experiment,
                                            const std::vector<std::string>& words,
                                            std::optional<std::uint64_t> seed,
                                            const SweepCommandOptions& o, const fs::path& dir) {
  std::vector<std::string> c = {cnclab, "sweep", experiment.string()};
  c.insert(c.end(), words.begin(), words.end());
  c.insert(c.end(), {"--dir", dir.string(), "--out",
                     results_root(o.common.results_dir, o.common.profile).string(), "--data-dir",
                     o.common.datasets_dir.string()});
  const auto add = [&c](const char* option, const std::string& value) {
    c.push_back(option);
    c.push_back(value);
  };
  if (!o.common.profile.empty()) add("--profile", o.common.profile);
  if (seed) add("--seed", std::to_string(*seed));
  if (o.repeats) add("--repeats", std::to_string(*o.repeats));
  if (o.trials) add("--trials", std::to_string(*o.trials));
  if (o.method) add("--method", *o.method);
  if (o.objective) add("--objective", *o.objective);
  if (o.sweep_seed) add("--sweep-seed", std::to_string(*o.sweep_seed));
  if (o.trial_timeout > 0) add("--trial-timeout", std::to_string(o.trial_timeout));
  if (o.retry_failed) c.push_back("--retry-failed");
  return c;
}

// Submits the array (when it has tasks), then the final job after it and
// after the earlier arrays still in flight; the submission counts (job.yaml)
// only once sbatch accepted the array. A rejected final job is a warning for
// `sweep --slurm` (merge by hand) and an error within `reproduce --slurm`.
void submit_scripts(SlurmSubmission& sub, const fs::path& dir, const EarlierJobs& earlier,
                    const SweepSlurmRequest& request, SweepSlurmResult& result, std::ostream& out,
                    std::ostream& log) {
  std::string after = "afterany";
  if (!sub.tasks.empty()) {
    std::vector<std::string> array_argv = {"sbatch", "--parsable"};
    if (!request.after.empty()) {
      array_argv.insert(array_argv.end(),
                        {"--dependency=" + request.after, "--kill-on-invalid-dep=yes"});
    }
    array_argv.push_back((sub.folder / "sweep.sbatch").string());
    const ToolRun array = run_tool(array_argv);
    if (array.exit_code != 0) {
      std::error_code ec;
      fs::remove_all(sub.folder, ec);
      throw Error("sbatch rejected the job array (exit " + std::to_string(array.exit_code) +
                  "): " + tool_message(array) + "; nothing was submitted for " + dir.string());
    }
    result.array_job = parsed_job_id(array);
    record_jobs(sub, result.array_job, "");
    after += ":" + result.array_job;
  }
  for (const auto& id : earlier.arrays) after += ":" + id;
  // Within reproduce with no array (its trials all done or in flight), the
  // final job waits for the upstream jobs itself (',': both conditions).
  std::string dependency = after == "afterany" ? "" : after;
  if (sub.tasks.empty() && !request.after.empty()) {
    dependency += (dependency.empty() ? "" : ",") + request.after;
  }
  std::vector<std::string> final_argv = {"sbatch", "--parsable"};
  if (!dependency.empty()) final_argv.push_back("--dependency=" + dependency);
  final_argv.insert(final_argv.end(),
                    {"--kill-on-invalid-dep=yes", (sub.folder / "merge.sbatch").string()});
  const ToolRun merge = run_tool(final_argv);
  if (merge.exit_code == 0) {
    result.final_job = parsed_job_id(merge);
    if (!sub.tasks.empty()) record_jobs(sub, result.array_job, result.final_job);
    // Earlier merge jobs still pending are redundant now (scancel ignores
    // those that already ran).
    for (const auto& id : earlier.merges) {
      try {
        run_tool({"scancel", "--state=PENDING", id});
      } catch (const Error&) {
        // No scancel: the earlier merge runs too; the new one runs last.
      }
    }
  } else if (!request.final_command.empty()) {
    throw Error("sbatch rejected the final job of " + dir.string() + " (exit " +
                std::to_string(merge.exit_code) + "): " + tool_message(merge) +
                (result.array_job.empty() ? ""
                                          : "; its array job " + result.array_job +
                                                " was submitted and is recorded there"));
  } else {
    log << "warning: sbatch rejected the merge job: " << tool_message(merge)
        << "; when the array has ended run: cnclab sweep merge " << dir.string() << "\n";
    result.final_rejected = true;
  }
  if (!sub.tasks.empty()) {
    out << "submitted " << sub.folder.filename().string() << ": array job " << result.array_job
        << " (" << sub.tasks.size() << " task" << (sub.tasks.size() == 1 ? "" : "s") << ")";
    if (!result.final_job.empty()) out << ", merge job " << result.final_job << " after it";
  } else {
    out << "submitted the final job " << result.final_job << " of " << dir.string();
  }
  out << "\nstatus: cnclab status " << dir.string() << "\n";
}

void check_sbatch_paths(const fs::path& dir) {
  for (const fs::path& p : {fs::current_path(), fs::absolute(dir)}) {
    if (p.string().find_first_of(" \t\n%") != std::string::npos) {
      throw ConfigError(p.string() +
                        ": a path with spaces or '%' cannot go on an #SBATCH line; choose "
                        "another --dir or working folder");
    }
  }
}

// A model-based sweep's worker tasks (model_search.hpp): one per trial the
// study still lacks (at most --tasks, at most kMaxArrayTasks), less its
// worker tasks queued or running; tasks.txt holds "study" per task. Each
// task asks until the study has its trials, so a surplus task ends at once.
SubmitSelection study_tasks_to_submit(const PreparedSweep& p, const SlurmOptions& slurm,
                                      const SlurmQueueView& v) {
  SubmitSelection sel;
  sel.done = study_finished(p.plan, p.dir);
  for (const auto& s : v.submissions) {
    for (std::size_t k = 0; k < s.tasks.size(); ++k) {
      const auto it = v.states.find(task_key(s, k));
      if (it != v.states.end() && slurm_phase(it->second) != SlurmPhase::ended) ++sel.in_flight;
    }
  }
  const std::size_t missing = p.spec.trials > sel.done ? p.spec.trials - sel.done : 0;
  std::size_t n = missing > sel.in_flight ? missing - sel.in_flight : 0;
  n = std::min(n, slurm.tasks > 0 ? slurm.tasks : kMaxArrayTasks);
  sel.ids.assign(n, "study");
  return sel;
}

}  // namespace

// Job names: letters, digits, '-', '_' (sbatch's #SBATCH lines split at spaces).
std::string slurm_job_name(const std::string& experiment, const char* suffix) {
  std::string name = "cnclab-" + experiment;
  for (char& ch : name) {
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '_') ch = '_';
  }
  return name + suffix;
}

std::string submit_batch(const std::vector<std::string>& args, const std::string& what) {
  std::vector<std::string> argv = {"sbatch", "--parsable"};
  argv.insert(argv.end(), args.begin(), args.end());
  const ToolRun r = run_tool(argv);
  if (r.exit_code != 0) {
    throw Error("sbatch rejected " + what + " (exit " + std::to_string(r.exit_code) +
                "): " + tool_message(r));
  }
  return parsed_job_id(r);
}

void check_slurm_clients() {
  for (const char* tool : {"sbatch", "squeue", "scontrol"}) {
    if (!find_on_path(tool)) {
      throw Error(std::string(tool) +
                  " not found on PATH: --slurm needs Slurm's client commands (run it on a "
                  "login node, or use --dry-run to see the scripts)");
    }
  }
}

SweepSlurmResult submit_sweep_slurm(const fs::path& experiment,
                                    const std::vector<std::string>& words,
                                    std::optional<std::uint64_t> seed, const SweepCommandOptions& o,
                                    const SlurmOptions& command_line,
                                    const SweepSlurmRequest& request, std::ostream& out,
                                    std::ostream& log) {
  const PreparedSweep prepared = prepare_sweep(experiment, words, seed, o);
  const bool study = model_based(prepared.plan);
  const SlurmOptions slurm = resolve_slurm_options(command_line, experiment, o.common.profile);
  SweepSlurmResult result;
  result.dir = prepared.dir;
  const fs::path& dir = prepared.dir;
  if (study) check_study_settings(prepared.plan, prepared.spec);  // before any file or job
  if (slurm.dry_run) {
    if (fs::exists(dir / "sweep.yaml") && load_plan(dir).hash() != prepared.plan.hash()) {
      store_plan(dir, prepared.plan);  // throws: another sweep's folder
    }
  } else {
    store_plan(dir, prepared.plan);
  }
  const SlurmQueueView view = slurm_queue_view(dir, !slurm.dry_run);
  const SubmitSelection sel = study ? study_tasks_to_submit(prepared, slurm, view)
                                    : trials_to_submit(prepared.plan, dir, o, view);
  result.total = study ? prepared.spec.trials : prepared.plan.trials.size();
  result.to_submit = sel.ids.size();
  result.done = sel.done;
  result.in_flight = sel.in_flight;
  const std::size_t total = result.total;
  // What is submitted and why: trials, or a study's worker tasks.
  const std::string counts =
      study ? std::to_string(sel.done) + " of " + std::to_string(total) +
                  " study trials complete or pruned, " + std::to_string(sel.in_flight) +
                  " worker task(s) queued or running"
            : std::to_string(sel.done) + " done, " + std::to_string(sel.in_flight) + " in flight";
  const std::string what =
      study ? std::to_string(sel.ids.size()) + " worker task(s)"
            : std::to_string(sel.ids.size()) + " of " + std::to_string(total) + " trials";
  if (sel.ids.empty() && request.final_command.empty()) {
    if (study) {
      out << "nothing to submit for " << dir.string() << ": " << counts << "\n";
    } else {
      out << "nothing to submit for " << dir.string() << ": " << sel.done << " of " << total
          << " trials done, " << sel.in_flight << " queued or running\n";
    }
    return result;
  }
  if (slurm.tasks == 0 && sel.ids.size() > kMaxArrayTasks) {
    throw ConfigError(std::to_string(sel.ids.size()) + " trials to submit: more than " +
                      std::to_string(kMaxArrayTasks) + " array tasks; give --tasks N");
  }
  const auto tasks = split_into_tasks(sel.ids, study ? 0 : slurm.tasks);
  const std::string cnclab = fs::read_symlink("/proc/self/exe").string();
  check_sbatch_paths(dir);
  SlurmArrayScript array;
  // squeue shows the sweep's name (a kind: sweep file's), else the experiment's.
  const std::string& name = prepared.name.empty() ? prepared.plan.experiment : prepared.name;
  array.job_name = slurm_job_name(name, "");
  array.workdir = fs::current_path();
  array.tasks = tasks.size();
  array.task_command = array_task_command(cnclab, experiment, words, seed, o, dir);
  array.study = study;
  const auto final_script = [&](const fs::path& submission) {
    if (request.final_command.empty()) {
      return merge_script(slurm, slurm_job_name(name, "-merge"), array.workdir, submission, cnclab,
                          dir);
    }
    return job_script(
        slurm, {slurm_job_name(name, "-final"), "the sweep's result once its array has ended",
                array.workdir, submission / "logs" / "final.out", request.final_command});
  };
  if (slurm.dry_run) {
    array.submission = dir / "slurm" / "submit-NNN";
    out << "# dry run: nothing written or submitted; " << what << " to submit (" << counts << ")\n";
    if (!tasks.empty()) {
      if (!request.after.empty()) {
        out << "# sbatch --parsable --dependency=" << request.after << " --kill-on-invalid-dep=yes "
            << (array.submission / "sweep.sbatch").string() << "\n";
      }
      out << array_script(slurm, array) << "# tasks.txt:\n";
      for (const auto& ids : tasks) {
        out << "#   ";
        for (std::size_t k = 0; k < ids.size(); ++k) out << (k ? "," : "") << ids[k];
        out << "\n";
      }
    }
    if (!request.final_command.empty()) out << final_script(array.submission);
    return result;
  }
  SlurmSubmission sub = create_submission(dir, tasks);
  array.submission = sub.folder;
  if (!tasks.empty())
    write_text_atomically(sub.folder / "sweep.sbatch", array_script(slurm, array));
  write_text_atomically(sub.folder / "merge.sbatch", final_script(sub.folder));
  if (study) {
    out << dir.string() << ": " << what << " to submit (" << counts << ")\n";
  } else {
    out << dir.string() << ": " << what << " to submit (" << sel.done << " done, " << sel.in_flight
        << " queued or running)\n";
  }
  submit_scripts(sub, dir, earlier_jobs(view), request, result, out, log);
  return result;
}

}  // namespace cnclab
