#include "cnclab/data/dataset_commands.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/data/constant_targets.hpp"
#include "cnclab/data/dataset_cache.hpp"
#include "cnclab/data/dataset_file.hpp"

namespace cnclab {
namespace fs = std::filesystem;

int dataset_generate_command(const fs::path& config, const std::vector<std::string>& overrides,
                             const std::optional<fs::path>& out_file, ProgressMode progress,
                             std::ostream& out, std::ostream& err) {
  ConfigDocument doc = ConfigDocument::load(config);
  for (const auto& text : overrides) doc.apply(parse_override(text));
  const ConfigReader root = doc.root();
  if (!root.has("dataset")) root.fail("dataset", "is required: {generator, seed?, options}");
  const DatasetSpec spec = read_dataset_spec(root.section("dataset"));
  const auto master = root.optional<std::uint64_t>("seed");
  for (const auto& key : root.keys()) {
    if (key != "dataset" && key != "seed") root.raw(key);  // another tool's section
  }
  doc.check_all_consumed();
  const std::uint64_t seed =
      spec.seed ? *spec.seed : (master ? derive_seed(*master, "generator") : 0);
  const fs::path path =
      out_file ? *out_file : fs::path("datasets") / (config.stem().string() + ".h5");

  const auto start = std::chrono::steady_clock::now();
  StagedProgress staged("dataset " + spec.generator->name(), err, {progress, 5.0, 0.1});
  const Dataset all = generate_dataset(spec, seed, staged.callback());
  Dataset d = select_targets(all, spec.targets);
  for (const auto& t : selected_constant_targets(all, d, *spec.generator)) {
    err << "warning: " << constant_target_text(t) << "\n";
  }
  d.generator_config = dataset_config_text(*spec.generator, seed);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!path.parent_path().empty()) fs::create_directories(path.parent_path());
  write_dataset(path, d);
  char line[512];
  std::snprintf(line, sizeof line,
                "wrote %s: %zu samples, %td inputs, %td targets, generator %s (%.3f s), "
                "content hash %s\n",
                path.string().c_str(), d.num_samples(), d.inputs.rows(), d.targets.rows(),
                d.generator.c_str(), seconds, d.content_hash().c_str());
  out << line;
  return 0;
}

namespace {

std::string row_text(const std::string& name, const Eigen::Ref<const Eigen::RowVectorXd>& values,
                     const std::string& unit) {
  char line[256];
  std::snprintf(line, sizeof line, "  %-14s %14.6g %14.6g %14.6g  %s\n", name.c_str(),
                values.size() ? values.minCoeff() : 0.0, values.size() ? values.maxCoeff() : 0.0,
                values.size() ? values.mean() : 0.0, unit.c_str());
  return line;
}

void print_rows(const char* title, const Eigen::MatrixXd& m, const std::vector<std::string>& names,
                const std::vector<std::string>& units, std::ostream& out) {
  char header[256];
  std::snprintf(header, sizeof header, "%-16s %14s %14s %14s  %s\n", title, "min", "max", "mean",
                "unit");
  out << header;
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    out << row_text(names[static_cast<std::size_t>(i)], m.row(i),
                    units[static_cast<std::size_t>(i)]);
  }
}

// 20 equal bins over [min, max] with bars scaled to the fullest bin.
void print_histogram(const Eigen::Ref<const Eigen::RowVectorXd>& values, const std::string& name,
                     const std::string& unit, std::ostream& out) {
  constexpr int kBins = 20, kBar = 40;
  const double lo = values.minCoeff(), hi = values.maxCoeff();
  const double width = hi > lo ? (hi - lo) / kBins : 1.0;
  std::vector<std::size_t> count(kBins, 0);
  for (Eigen::Index j = 0; j < values.size(); ++j) {
    const int bin = std::min(kBins - 1, static_cast<int>((values(j) - lo) / width));
    ++count[static_cast<std::size_t>(bin)];
  }
  const std::size_t most = *std::max_element(count.begin(), count.end());
  out << "histogram of " << name << " [" << unit << "]\n";
  for (int b = 0; b < kBins; ++b) {
    const auto n = count[static_cast<std::size_t>(b)];
    const int bar = most ? static_cast<int>((kBar * n + most - 1) / most) : 0;
    char line[256];
    std::snprintf(line, sizeof line, "  [%10.4g, %10.4g%c %7zu  %s\n", lo + b * width,
                  lo + (b + 1) * width, b + 1 == kBins ? ']' : ')', n,
                  std::string(static_cast<std::size_t>(bar), '#').c_str());
    out << line;
  }
}

}  // namespace

void print_dataset_summary(const Dataset& d, const std::string& source, std::ostream& out) {
  out << "dataset    " << source << "\ngenerator  " << d.generator << "\nsamples    "
      << d.num_samples() << "\ninputs     " << d.inputs.rows() << "\ntargets    "
      << d.targets.rows() << "\nmetadata   " << d.metadata.rows()
      << " columns (stored beside the inputs, not inputs)\ncontent    " << d.content_hash()
      << "\n\n";
  if (d.num_samples() == 0) return;
  print_rows("inputs", d.inputs, d.input_names, d.input_units, out);
  print_rows("targets", d.targets, d.target_names, d.target_units, out);
  if (d.has_metadata()) print_rows("metadata", d.metadata, d.metadata_names, d.metadata_units, out);
  out << "\n";
  print_histogram(d.targets.row(0), d.target_names.front(), d.target_units.front(), out);
  const Eigen::Index convex = d.metadata_row("convex");
  if (convex >= 0) {
    const auto n = static_cast<double>(d.num_samples());
    const double c = (d.metadata.row(convex).array() > 0.5).cast<double>().sum();
    char line[256];
    std::snprintf(line, sizeof line,
                  "\nconvex/concave split: convex %.0f (%.1f %%), concave %.0f (%.1f %%)\n", c,
                  100.0 * c / n, n - c, 100.0 * (n - c) / n);
    out << line;
    for (const bool want : {true, false}) {
      double lo = INFINITY, hi = -INFINITY;
      for (Eigen::Index j = 0; j < d.metadata.cols(); ++j) {
        if ((d.metadata(convex, j) > 0.5) != want) continue;
        lo = std::min(lo, d.targets(0, j));
        hi = std::max(hi, d.targets(0, j));
      }
      if (lo > hi) continue;
      std::snprintf(line, sizeof line, "  %-8s %s in [%.6g, %.6g] %s\n",
                    want ? "convex" : "concave", d.target_names.front().c_str(), lo, hi,
                    d.target_units.front().c_str());
      out << line;
    }
  }
}

int dataset_show_command(const fs::path& file, std::ostream& out) {
  print_dataset_summary(read_dataset(file), file.string(), out);
  return 0;
}

}  // namespace cnclab
