#include "cnclab/studies/step_error/step_error_reference.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>

#include "cnclab/core/config.hpp"
#include "cnclab/report/tables.hpp"

namespace cnclab {
namespace {

// Bin edges may end in .inf ("> 20 %"), which ConfigReader's finite-number
// reads reject: read the list raw, allow +inf only as the last edge.
std::vector<double> read_edges(const ConfigReader& r) {
  const YAML::Node node = r.raw("edges");
  if (!node.IsSequence()) r.fail("edges", "expected a list of numbers");
  std::vector<double> edges;
  for (const auto& item : node) {
    double v = NAN;
    try {
      v = item.as<double>();
    } catch (const YAML::Exception&) {
      r.fail("edges", "expected a list of numbers");
    }
    if (std::isnan(v) || (std::isinf(v) && v < 0)) r.fail("edges", "NaN or -inf edge");
    if (!edges.empty() && std::isinf(edges.back())) r.fail("edges", ".inf only as the last edge");
    if (!edges.empty() && !(edges.back() < v)) r.fail("edges", "must be strictly increasing");
    edges.push_back(v);
  }
  return edges;
}

PaperBins read_bins(const ConfigReader& r) {
  PaperBins b;
  b.edges = read_edges(r);
  b.count = r.require<std::vector<double>>("count");
  b.percent = r.require<std::vector<double>>("percent");
  r.check(b.edges.size() >= 2, "edges", "needs at least 2 edges");
  r.check(b.count.size() + 1 == b.edges.size(), "count", "needs one value per bin");
  r.check(b.percent.size() + 1 == b.edges.size(), "percent", "needs one value per bin");
  return b;
}

PaperBinTable read_bin_table(const ConfigReader& r) {
  return {read_bins(r.section("absolute_error_um")),
          read_bins(r.section("relative_error_percent"))};
}

PaperSurfaceText read_surface_text(const ConfigReader& r) {
  PaperSurfaceText t;
  const ConfigReader max = r.section("max_absolute_error_um");
  t.max_abs_at_0 = max.require<double>("at_0_percent");
  t.max_abs_at_15 = max.require<double>("at_15_percent");
  const ConfigReader share = r.section("share_below_1_um_percent");
  t.share_below_1um_at_0 = share.require<double>("at_0_percent");
  t.share_below_1um_at_15 = share.require<double>("at_15_percent");
  t.share_rel_below_10_at_15 = r.require<double>("share_relative_below_10_percent_at_15_percent");
  t.mean_abs_at_15 = r.require<double>("mean_absolute_error_um_at_15_percent");
  t.share_below_0_4um_at_15 = r.require<double>("share_below_0_4_um_percent_at_15_percent");
  return t;
}

std::map<std::string, double> read_surfaces_2_3(const ConfigReader& r) {
  return {{"surface2", r.require<double>("surface2")}, {"surface3", r.require<double>("surface3")}};
}

}  // namespace

Seed000Reference read_seed000_reference(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) {
    throw MissingResults(file.string() + ": reference file not found");
  }
  const ConfigDocument doc = ConfigDocument::load(file);
  const ConfigReader root = doc.root();
  Seed000Reference ref;
  // Descriptive parts the tables do not print; read so the file stays strict.
  root.require<std::string>("source");
  root.raw("surfaces");
  root.raw("network");

  const ConfigReader t2 = root.section("table2_p_vs_mse");
  ref.table2_p = t2.require<std::vector<double>>("p");
  ref.table2_mse = t2.require<std::vector<double>>("mse");
  t2.check(ref.table2_mse.size() == ref.table2_p.size(), "mse", "needs one value per p");
  ref.figure5_final_mse = root.require<double>("figure5_final_mse");

  const ConfigReader t3 = root.section("table3_surface1");
  ref.table3 = read_bin_table(t3);
  ref.table3_max_abs_um = t3.require<double>("max_absolute_error_um");
  ref.table3_share_below_0_5um = t3.require<double>("share_below_0_5_um_percent");
  ref.table3_share_rel_above_10 = t3.require<double>("share_relative_above_10_percent");

  const ConfigReader t45 = root.section("table4_table5_test_sizes");
  ref.fine_tune_percent = t45.require<std::vector<double>>("fine_tune_percent");
  ref.test_samples = t45.require<std::vector<double>>("test_samples");
  t45.check(ref.test_samples.size() == ref.fine_tune_percent.size(), "test_samples",
            "needs one value per fine_tune_percent");

  ref.surface2 = read_surface_text(root.section("surface2_text"));
  ref.surface3 = read_surface_text(root.section("surface3_text"));
  ref.table6 = read_bin_table(root.section("table6_surface2_15_percent"));
  ref.table7 = read_bin_table(root.section("table7_surface3_15_percent"));

  const ConfigReader t8 = root.section("table8_time_s");
  ref.table8_geometric = read_surfaces_2_3(t8.section("geometric_method"));
  ref.table8_proposed = read_surfaces_2_3(t8.section("proposed_method"));
  ref.checks = root.require<std::vector<std::string>>("checks");
  doc.check_all_consumed();
  return ref;
}

}  // namespace cnclab
