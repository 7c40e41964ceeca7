// Per-trial overhead of the sweep machinery, on the friedman experiment's
// default dataset (2000 samples) and network: everything a sweep does for a
// trial besides training it. Prints one line per stage, "stage <name> ms
// <median wall> cpu_ms <median CPU of this process and its children>", and
// the totals (medians of REPEATS runs). CPU time shows the cost when other
// processes compete for the cores; wall time includes fsync waits.
//   resolve   load_experiment with two overrides (YAML, includes, validation, hash)
//   cache_hit obtain_dataset when the cached file exists (read + verify hash)
//   fork      fork + exit + waitpid of a trial process
//   write     write_result of a complete result (atomic: temp, fsync, rename)
//   outcome   read_trial_outcome (the resume check / summary read of a trial)
// scripts/bench_sweep runs this and the jobs=1 vs jobs=2 sweep timing.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <vector>

#include "cnclab/core/hash.hpp"
#include "cnclab/data/dataset_cache.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/runner.hpp"
#include "cnclab/sweep/sweep_plan.hpp"
#include "cnclab/sweep/sweep_summary.hpp"

namespace fs = std::filesystem;
using namespace cnclab;

namespace {

// User + system CPU time of this process and its waited-for children [ms].
double cpu_ms() {
  double ms = 0;
  for (int who : {RUSAGE_SELF, RUSAGE_CHILDREN}) {
    rusage u{};
    getrusage(who, &u);
    for (const timeval& t : {u.ru_utime, u.ru_stime}) ms += t.tv_sec * 1e3 + t.tv_usec * 1e-3;
  }
  return ms;
}

struct Timing {
  double wall_ms, cpu_ms;
};

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

Timing measure(int repeats, const std::function<void(int)>& f) {
  std::vector<double> wall, cpu;
  for (int i = 0; i < repeats; ++i) {
    const double c0 = cpu_ms();
    const auto t0 = std::chrono::steady_clock::now();
    f(i);
    wall.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    cpu.push_back(cpu_ms() - c0);
  }
  return {median(wall), median(cpu)};
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 21;
  const fs::path experiment = argc > 2 ? argv[2] : "experiments/friedman/friedman1_mlp.yaml";
  const fs::path dir =
      fs::temp_directory_path() / ("cnclab_bench_sweep_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::vector<std::string> overrides = {"trainer.learning_rate=0.001",
                                              "model.dropout.keep_probability=0.9"};

  // One real trial (1 epoch) gives a realistic result to write and read.
  LoadedExperiment trial = load_experiment(experiment, {"trainer.epochs=1"});
  RunOptions run;
  run.results_dir = dir / "results";
  run.datasets_dir = dir / "datasets";
  PlannedTrial planned;
  planned.id = hash_hex(trial.resolved_yaml);
  run.result_file = trial_result_path(dir / "sweep", planned.id);
  run_experiment(trial, run);
  const RunRecord record = read_result(run.result_file);

  const std::vector<std::pair<const char*, Timing>> stages = {
      {"resolve", measure(repeats, [&](int) { load_experiment(experiment, overrides); })},
      {"cache_hit", measure(repeats,
                            [&](int) {
                              obtain_dataset(trial.spec.dataset, generator_seed(trial.spec),
                                             run.datasets_dir, nullptr);
                            })},
      {"fork", measure(repeats,
                       [&](int) {
                         const pid_t pid = fork();
                         if (pid == 0) _exit(0);
                         int status = 0;
                         waitpid(pid, &status, 0);
                       })},
      {"write",
       measure(repeats,
               [&](int i) { write_result(dir / "w" / (std::to_string(i) + ".h5"), record); })},
      {"outcome", measure(repeats, [&](int) { read_trial_outcome(dir / "sweep", planned); })},
  };
  Timing total{0, 0};
  for (const auto& [name, t] : stages) {
    std::printf("stage %s ms %.3f cpu_ms %.3f\n", name, t.wall_ms, t.cpu_ms);
    total.wall_ms += t.wall_ms;
    total.cpu_ms += t.cpu_ms;
  }
  std::printf("stage total ms %.3f cpu_ms %.3f\n", total.wall_ms, total.cpu_ms);
  fs::remove_all(dir);
  return 0;
}
