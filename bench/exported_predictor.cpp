#include "exported_predictor.hpp"

#include <dlfcn.h>
#include <stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/deploy/c_export.hpp"
#include "cnclab/deploy/sequence_extension.hpp"
#include "cnclab/studies/contour_error/contour_predictor.hpp"
#include "common/counting_malloc.hpp"  // interposes malloc to count (not under a sanitizer)

namespace cnclab::bench {
namespace fs = std::filesystem;
namespace {

constexpr const char* kName = "bench_narx";
using InitFn = void (*)(void*);
using StepFn = int (*)(void*, const double*, double*);
using ContourFn = int (*)(const double*, const double*, const double*, const double*, double*);

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::string command_output(const std::string& command) {
  std::string out;
  if (FILE* p = popen(command.c_str(), "r")) {
    char buffer[256];
    while (std::fgets(buffer, sizeof buffer, p) != nullptr) out += buffer;
    pclose(p);
  }
  return out;
}

// The bench's networks as a model of the following_error dataset: physical
// columns v_ref [mm/s] and e_ref [um] with the normalisers' ranges.
DeployedModel model_of(const NarxAxisModel (&models)[2]) {
  DeployedModel m;
  m.kind = ModelKind::narx;
  m.experiment = kName;
  m.generator = "following_error";
  m.narx = models[0].options;
  const char* axes[] = {"x", "y"};
  for (int a = 0; a < 2; ++a) {
    const std::string axis = axes[a];
    m.networks.push_back({axis, "v_" + axis, "e_" + axis, models[a].params});
    m.input_names.push_back("v_" + axis);
    m.target_names.push_back("e_" + axis);
    m.physical_inputs.push_back(
        {"v_ref_" + axis, "mm/s", models[a].input.x_min()[0], models[a].input.x_max()[0]});
    m.physical_targets.push_back({"e_ref_" + axis, "um", models[a].output.x_min()[0] * 1000.0,
                                  models[a].output.x_max()[0] * 1000.0});
  }
  m.input_units = m.target_units = {"1", "1"};
  m.extension = find_sequence_extension("following_error");
  if (m.extension == nullptr) throw Error("the following_error extension is not registered");
  return m;
}

}  // namespace

long allocation_count() {
  return testing::heap_allocations();
}

ExportedTiming time_exported_predictor(const NarxAxisModel (&models)[2],
                                       const std::vector<Vec2>& velocity,
                                       const std::vector<PathPoint>& reference, int repeats) {
  const DeployedModel m = model_of(models);
  const CExport c = c_export(m, {kName, CPrecision::float64});
  char pattern[] = "/tmp/cnclab_bench_export_XXXXXX";
  if (mkdtemp(pattern) == nullptr) throw Error("cannot make a temporary folder");
  const fs::path dir = pattern;
  std::ofstream(dir / (std::string(kName) + ".h")) << c.header;
  std::ofstream(dir / (std::string(kName) + ".c")) << c.source;
  ExportedTiming t;
  const fs::path library = dir / "libexported.so";
  t.compile = std::string(CNCLAB_C_COMPILER) + " " + CNCLAB_C_FLAGS + " -std=c99 -fPIC -shared";
  const std::string cmd = t.compile + " -o " + library.string() + " " +
                          (dir / (std::string(kName) + ".c")).string() + " -lm";
  if (std::system(cmd.c_str()) != 0) throw Error("the export does not compile: " + cmd);
  // "                 U tanh@GLIBC_2.2.5" lines: the symbol is the last word.
  std::istringstream nm(command_output("nm -D --undefined-only " + library.string()));
  for (std::string line; std::getline(nm, line);) {
    std::istringstream words(line);
    std::string word, last;
    while (words >> word) last = word;
    if (!last.empty()) t.imports.push_back(last.substr(0, last.find('@')));
  }
  void* handle = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) throw Error(std::string("dlopen: ") + dlerror());
  const auto init = reinterpret_cast<InitFn>(dlsym(handle, "bench_narx_init"));
  const auto step = reinterpret_cast<StepFn>(dlsym(handle, "bench_narx_step"));
  const auto contour = reinterpret_cast<ContourFn>(dlsym(handle, "bench_narx_contour_error"));
  if (!init || !step || !contour) throw Error("the export lacks its functions");

  // bench_narx_state: v[2][d0 + D_V], e[2][D_E] doubles.
  const NarxOptions& o = m.narx;
  std::vector<double> state(2 * (o.first_input_delay + o.input_delays + o.feedback_delays));
  const std::size_t n = velocity.size();
  std::vector<double> per_tick;
  double checksum = 0;
  double out[2], eps = 0;
  // One tick of the export: both networks, then the contour estimate.
  const auto tick = [&](std::size_t k) {
    const PathPoint& p = reference[k];
    const double in[2] = {velocity[k].x(), velocity[k].y()};
    const double position[2] = {p.position.x(), p.position.y()};
    const double d1[2] = {p.d1.x(), p.d1.y()}, d2[2] = {p.d2.x(), p.d2.y()};
    step(state.data(), in, out);
    contour(position, d1, d2, out, &eps);
  };
  for (int r = 0; r < std::max(repeats, 3); ++r) {
    init(state.data());
    const long before = allocation_count();
    const double t0 = cpu_seconds();
    for (std::size_t k = 0; k < n; ++k) {
      tick(k);
      checksum += eps;
    }
    const double seconds = cpu_seconds() - t0;
    if (before >= 0) t.allocations = std::max(t.allocations, allocation_count() - before);
    per_tick.push_back(seconds / static_cast<double>(n));
  }
  std::sort(per_tick.begin(), per_tick.end());
  t.tick_seconds = per_tick[per_tick.size() / 2];

  // Agreement with the internal predictor over the series.
  ContourPredictor internal(models[0], models[1]);
  init(state.data());
  ContourPrediction p;
  for (std::size_t k = 0; k < n; ++k) {
    tick(k);
    if (internal.step(velocity[k], reference[k], p) != PredictorStatus::ok) continue;
    for (int a = 0; a < 2; ++a) {
      t.max_error_diff = std::max(t.max_error_diff, std::abs(out[a] - p.following_error[a] * 1e3));
    }
    t.max_contour_diff =
        std::max(t.max_contour_diff, std::abs(eps - std::abs(p.contour_error) * 1e3));
  }
  if (!std::isfinite(checksum)) t.max_contour_diff = NAN;
  dlclose(handle);
  fs::remove_all(dir);
  return t;
}

}  // namespace cnclab::bench
