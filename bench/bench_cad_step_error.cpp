// Step-error dataset generation from a STEP face against the same surface
// from YAML (target: within 2x), single thread, seed 000's tool
// path (200 lines x 100 CC points, R = 5 mm, K = 20; a third argument
// LINESxPOINTS, e.g. 800x400, for a longer path). Each timing is the whole
// path of an experiment: reading the `dataset` section (YAML surface file, or
// STEP file through OCCT: parse, NURBS conversion, the path planned on the
// face) and generating the dataset. The STEP files are written
// from configs/surfaces/*.yaml into a temporary folder first. Times are CPU
// seconds of this process and its children (the STEP reader's forked probe,
// cad/occt_shape_io.cpp), so a loaded machine does not skew the ratio.
// Medians over REPEATS (default 5). Run via `scripts/bench_cad_step_error
// --in-process`; that script's own figures (each side a fresh `cnclab dataset
// generate` process) are what users see and the benchmark's figure.
//
// Where the STEP side's extra time goes: the read (fork, OCCT's STEP session
// set-up, parse and transfer in the child, the BRep handover; about 50 ms
// whatever the path's length) and the path's on-face classification (once
// per dataset; a YAML surface has no trims to classify against). And an effect of this long-lived
// process that `cnclab run` does not have: glibc raises its mmap threshold when the first dataset
// (11.5 MB) is freed, so later datasets reuse warm heap pages; the STEP read's fork write-protects
// them, and the next dataset pays a page fault per 4 KiB page (with the fork itself about 80 ms
// here, on a shared VM: a fork doing nothing before each YAML run costs as much). A fresh process
// maps each dataset new on both sides. GLIBC_TUNABLES= glibc.malloc.mmap_threshold=131072 (a fixed
// threshold) measures that case.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cnclab/cad/cad_export.hpp"
#include "cnclab/cad/cad_surface.hpp"
#include "cnclab/core/config.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/data/generator.hpp"
#include "cnclab/geometry/surface_config.hpp"
#include "cnclab/geometry/tool_path.hpp"

namespace {

using namespace cnclab;
namespace fs = std::filesystem;

// User + system CPU seconds of this process and its waited-for children.
double cpu_seconds() {
  double total = 0;
  for (const int who : {RUSAGE_SELF, RUSAGE_CHILDREN}) {
    rusage u{};
    ::getrusage(who, &u);
    total += static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
             1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
  }
  return total;
}

template <class F>
double median_seconds(int repeats, F&& f) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const double start = cpu_seconds();
    f();
    t.push_back(cpu_seconds() - start);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

// Reads the dataset section as an experiment would, then generates.
void generate(const std::string& surface, const ToolPathOptions& path) {
  const std::string config =
      "dataset:\n  generator: step_error\n  options:\n    surface: " + surface +
      "\n    lines: " + std::to_string(path.lines) +
      "\n    points_per_line: " + std::to_string(path.points_per_line) +
      "\n    tool_radius: 5\n    curve_points: 20\n";
  ConfigDocument doc = ConfigDocument::parse(config, "bench.yaml");
  const auto generator = read_generator(doc.root().section("dataset"));
  Rng unused(0);
  const Dataset d = generator->generate(unused);
  if (d.num_samples() != path.lines * (path.points_per_line - 1)) std::abort();
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const std::string root = argc > 2 ? argv[2] : CNCLAB_SOURCE_DIR;
  ToolPathOptions path;  // seed 000's 200 x 100
  if (argc > 3 && std::sscanf(argv[3], "%zux%zu", &path.lines, &path.points_per_line) != 2) {
    std::fprintf(stderr, "LINESxPOINTS expected, e.g. 800x400; got %s\n", argv[3]);
    return 2;
  }
  path.validate();
  if (!cad_support_available()) {
    std::fprintf(stderr, "%s\n", cad_unavailable_message().c_str());
    return 2;
  }
  const fs::path dir =
      fs::temp_directory_path() / ("cnclab_bench_cad_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::printf("single thread, median of %d; %zu lines x %zu CC points, R = 5 mm, K = 20\n", repeats,
              path.lines, path.points_per_line);
  std::printf("%-9s %12s %12s %8s\n", "surface", "YAML [cpu s]", "STEP [cpu s]", "ratio");
  double worst = 0;
  for (const char* name : {"surface1", "surface2", "surface3"}) {
    const std::string yaml = root + "/configs/surfaces/" + name + ".yaml";
    const fs::path step = dir / (std::string(name) + ".step");
    {
      const ConfigDocument doc = ConfigDocument::load(yaml);
      std::ofstream(step) << cad_surface_text(read_nurbs_surface(doc.root()), CadFormat::step);
    }
    const double t_yaml = median_seconds(repeats, [&] { generate(yaml, path); });
    const double t_step =
        median_seconds(repeats, [&] { generate("{file: " + step.string() + ", face: 1}", path); });
    CadSurface cad;
    const double t_read = median_seconds(repeats, [&] { cad = read_cad_surface(step, 1); });
    const double t_plan =
        median_seconds(repeats, [&] { plan_tool_path(cad.surface, path, cad.context); });
    worst = std::max(worst, t_step / t_yaml);
    std::printf("%-9s %12.3f %12.3f %7.2fx   (STEP read %.3f, path planning on the face %.3f)\n",
                name, t_yaml, t_step, t_step / t_yaml, t_read, t_plan);
  }
  std::printf("largest ratio STEP / YAML: %.2fx (target <= 2x)\n", worst);
  fs::remove_all(dir);
  return 0;
}
