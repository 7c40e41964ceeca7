#include "cnclab/pipeline/reproduce_slurm.hpp"

#include <optional>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/experiment/experiment_graph.hpp"
#include "cnclab/experiment/result_store.hpp"
#include "cnclab/experiment/upstream.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/pipeline/slurm_sweep_submit.hpp"
#include "cnclab/sweep/slurm_fields.hpp"
#include "cnclab/sweep/slurm_queue.hpp"
#include "cnclab/sweep/slurm_reproduce_record.hpp"
#include "cnclab/sweep/slurm_submission.hpp"
#include "cnclab/sweep/slurm_tools.hpp"
#include "cnclab/sweep/sweep_job.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// Where a node of the graph stands for its dependents.
struct SlurmNodeState {
  bool blocked = false;             // no result can come (failed to load, upstream blocked)
  std::string job;                  // its job (submitted now or in flight); "" when reused
  std::optional<RunRecord> record;  // reused: its current result
  std::string name;
};

// The submission of one `reproduce --slurm`: scripts in one submit-NNN
// folder, each accepted job recorded at once (a rejected one stops it all).
class GraphSubmitter {
 public:
  GraphSubmitter(const CommandOptions& options, const SlurmOptions& slurm, std::ostream& out,
                 std::ostream& log)
      : o_(options),
        slurm_(slurm),
        out_(out),
        log_(log),
        store_(options.results_dir, options.profile),
        cnclab_(fs::read_symlink("/proc/self/exe").string()),
        workdir_(fs::current_path()),
        record_(read_reproduce_record(options.results_dir)) {
    // A submission must know what is in flight; a dry run shows it when it can.
    if (!slurm.dry_run) {
      jobs_ = squeue_jobs();
    } else if (find_on_path("squeue")) {
      try {
        jobs_ = squeue_jobs();
      } catch (const Error&) {
      }
    }
  }

  void submit_graph(const std::vector<GraphNode>& graph) {
    state_.resize(graph.size());
    for (std::size_t i = 0; i < graph.size(); ++i) submit_node(graph, i);
  }

  void submit_jobs(const std::vector<std::pair<fs::path, JobKind>>& jobs) {
    std::string after;  // jobs run after the graph, as locally
    for (const auto& s : state_) {
      if (!s.job.empty()) after += ":" + s.job;
    }
    if (!after.empty()) after = "afterany" + after;
    for (const auto& [file, kind] : jobs) {
      try {
        if (kind.kind == "sweep") {
          submit_sweep(file, after);
        } else {
          submit_plain(file, kind.kind, file.stem().string(), "", after, kind.kind + " job");
        }
      } catch (const ConfigError& e) {
        rows_.push_back({file.string(), "CONFIG ERROR", "", "", e.what()});
        exit_code_ = 2;
      }
    }
  }

  ReproduceSlurmRun result() const { return {rows_, submitted_, exit_code_}; }

 private:
  void submit_node(const std::vector<GraphNode>& graph, std::size_t i) {
    const GraphNode& node = graph[i];
    SlurmNodeState& s = state_[i];
    s.name = node.experiment ? node.experiment->spec.name : node.file.string();
    if (!node.experiment) {
      s.blocked = true;
      rows_.push_back(
          {s.name, node.config_error ? "CONFIG ERROR" : "ERROR", "", "", node.load_error});
      exit_code_ = node.config_error ? 2 : std::max(exit_code_, 1);
      return;
    }
    std::vector<std::string> deps, dep_names;
    std::vector<CurrentUpstream> upstream;
    for (std::size_t j : node.upstream) {
      const SlurmNodeState& up = state_[j];
      if (up.blocked) {
        s.blocked = true;
        rows_.push_back({s.name, "skipped", "", "", "upstream " + up.name + " has no result"});
        exit_code_ = std::max(exit_code_, 1);
        return;
      }
      if (!up.job.empty()) {
        deps.push_back(up.job);
        dep_names.push_back(up.name);
      } else {
        upstream.push_back({up.name, result_identity(*up.record)});
      }
    }
    const LoadedExperiment& exp = *node.experiment;
    std::string why;
    if (!deps.empty()) {
      why = "upstream ";
      for (std::size_t k = 0; k < dep_names.size(); ++k) why += (k ? ", " : "") + dep_names[k];
      why += " submitted";
    } else if (o_.force) {
      why = "--force";
    } else {
      CurrentResult current = current_result(exp, upstream, store_);
      if (current.record) {
        s.record = std::move(current.record);
        rows_.push_back({s.name, "reused", "", "", "config and upstream results unchanged"});
        return;
      }
      why = current.why;
    }
    std::string after;
    for (const auto& d : deps) after += ":" + d;
    if (!after.empty()) after = "afterok" + after;
    s.job = submit_plain(node.file, "run", s.name, result_path(exp, o_.results_dir).string(), after,
                         why);
  }

  // An experiment or `kind:` job as one job running `cnclab run FILE`
  // (unless its recorded job for the same output is still queued or
  // running). Returns the job others wait for.
  std::string submit_plain(const fs::path& file, const std::string& kind, const std::string& name,
                           const std::string& output, const std::string& after,
                           const std::string& why) {
    if (const auto job = in_flight(file, output)) {
      rows_.push_back({name, "in flight", *job, "", "its job is still queued or running"});
      return *job;
    }
    const fs::path script = folder() / (script_stem(name) + ".sbatch");
    SlurmJobScript js;
    js.job_name = slurm_job_name(name, "");
    js.what = (kind == "run" ? "the result of " : "the " + kind + " job ") + file.string();
    js.workdir = workdir_;
    js.log = folder() / "logs" / (script_stem(name) + "-%j.out");
    js.command = run_command_words(file);
    const SlurmOptions slurm = resolve_slurm_options(slurm_, file, o_.profile);
    const std::string job = submit(job_script(slurm, js), script, after, name);
    rows_.push_back({name, action(), job, shown_after(after), why});
    remember(file, {name, output, job, "", script.string()});
    return job;
  }

  // A `kind: sweep` job: its array (trials neither done nor in flight) and
  // its final `cnclab run FILE`, or reused when finished.
  void submit_sweep(const fs::path& file, const std::string& after) {
    const SweepJob job = load_sweep_job(file, {}, o_.profile);
    const SweepJobState state = sweep_job_state(job, o_.results_dir);
    const ResultStore store(o_.results_dir, job.profile);
    std::error_code ec;
    if (!o_.force && state.finished() &&
        fs::exists(store.path_of(sweep_job_key(job, state.plan)), ec)) {
      rows_.push_back(
          {job.name, "reused", "", "", "sweep plan unchanged, every trial has a result"});
      return;
    }
    if (const auto id = in_flight(file, state.dir.string())) {
      rows_.push_back({job.name, "in flight", *id, "", "its final job is still queued or running"});
      return;
    }
    SweepCommandOptions so;
    so.common = o_;
    SweepSlurmRequest request;
    request.after = after;
    request.final_command = run_command_words(file);
    std::ostringstream notes;
    const SweepSlurmResult r = submit_sweep_slurm(file, {}, std::nullopt, so, slurm_, request,
                                                  slurm_.dry_run ? out_ : notes, log_);
    if (!o_.quiet && !slurm_.dry_run) log_ << notes.str();
    const std::string counts = std::to_string(r.to_submit) + " of " + std::to_string(r.total) +
                               " trials submitted (" + std::to_string(r.done) + " done, " +
                               std::to_string(r.in_flight) + " in flight)";
    if (slurm_.dry_run) {
      rows_.push_back({job.name, action(), "{" + job.name + "}", shown_after(after), counts});
      return;
    }
    ++submitted_;
    rows_.push_back({job.name, "submitted", r.final_job,
                     r.array_job.empty() ? shown_after(after) : "array " + r.array_job, counts});
    remember(file,
             {job.name, state.dir.string(), r.final_job, r.array_job, (r.dir / "slurm").string()});
  }

  // The recorded job of `file` for the same output, when still queued or running.
  std::optional<std::string> in_flight(const fs::path& file, const std::string& output) const {
    const auto it = record_.find(reproduce_file_key(file));
    if (it == record_.end() || it->second.output != output) return std::nullopt;
    const auto state = jobs_.find(it->second.job);
    if (state == jobs_.end() || slurm_phase(state->second) == SlurmPhase::ended) {
      return std::nullopt;
    }
    return it->second.job;
  }

  // `cnclab run FILE` as the job runs it: the same results root, dataset
  // folder and profile as this command.
  std::vector<std::string> run_command_words(const fs::path& file) const {
    std::vector<std::string> c = {cnclab_,
                                  "run",
                                  file.string(),
                                  "--out",
                                  results_root(o_.results_dir, o_.profile).string(),
                                  "--data-dir",
                                  o_.datasets_dir.string()};
    if (!o_.profile.empty()) c.insert(c.end(), {"--profile", o_.profile});
    if (o_.regenerate) c.push_back("--regenerate");
    return c;
  }

  // Writes the script and submits it (a dry run prints both and returns
  // "{name}" as the job id).
  std::string submit(const std::string& text, const fs::path& script, const std::string& after,
                     const std::string& name) {
    std::vector<std::string> args;
    if (!after.empty()) {
      args.push_back("--dependency=" + after);
      args.push_back("--kill-on-invalid-dep=yes");
    }
    args.push_back(script.string());
    if (slurm_.dry_run) {
      out_ << "# sbatch --parsable";
      for (const auto& a : args) out_ << " " << a;
      out_ << "\n" << text;
      return "{" + name + "}";  // a dry run's job id: the name in braces
    }
    write_text_atomically(script, text);
    const std::string job = submit_batch(args, "the job of " + name);
    ++submitted_;
    return job;
  }

  void remember(const fs::path& file, const ReproduceJobEntry& entry) {
    if (slurm_.dry_run) return;
    record_[reproduce_file_key(file)] = entry;
    write_reproduce_record(o_.results_dir, record_);
  }

  // The submission folder, created on first use (a dry run names it only).
  const fs::path& folder() {
    if (folder_.empty()) {
      const fs::path root = reproduce_slurm_dir(o_.results_dir);
      folder_ = slurm_.dry_run ? root / "submit-NNN" : create_submission_folder(root).first;
    }
    return folder_;
  }

  std::string action() const { return slurm_.dry_run ? "submit" : "submitted"; }

  static std::string script_stem(const std::string& name) { return slurm_job_name(name, ""); }

  // "a, b" for the summary: the names of the jobs a dependency waits for.
  std::string shown_after(const std::string& after) const {
    const auto colon = after.find(':');
    if (colon == std::string::npos) return "";
    std::string ids = after.substr(colon + 1);
    for (char& c : ids) c = c == ':' ? ',' : c;
    return ids;
  }

  const CommandOptions& o_;
  const SlurmOptions& slurm_;
  std::ostream& out_;
  std::ostream& log_;
  const ResultStore store_;
  const std::string cnclab_;
  const fs::path workdir_;
  ReproduceRecord record_;
  SlurmTaskStates jobs_;  // single jobs Slurm still knows (squeue)
  std::vector<SlurmNodeState> state_;
  std::vector<ReproduceSlurmRow> rows_;
  fs::path folder_;
  std::size_t submitted_ = 0;
  int exit_code_ = 0;
};

}  // namespace

ReproduceSlurmRun submit_reproduce_slurm(const ReproduceInputs& inputs,
                                         const CommandOptions& options, const SlurmOptions& slurm,
                                         std::ostream& out, std::ostream& log) {
  const std::vector<GraphNode> graph = load_graph(inputs.files, options.profile);
  GraphSubmitter submitter(options, slurm, out, log);
  submitter.submit_graph(graph);
  submitter.submit_jobs(inputs.jobs);
  return submitter.result();
}

}  // namespace cnclab
