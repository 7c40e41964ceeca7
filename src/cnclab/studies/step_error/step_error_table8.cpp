#include "cnclab/studies/step_error/step_error_table8.hpp"

#include <map>
#include <string>

#include "cnclab/report/typed_table.hpp"
#include "cnclab/studies/step_error/step_error_timing.hpp"

namespace cnclab {
namespace fs = std::filesystem;
void print_step_error_table8(const StepErrorStudy& s, const TablesOptions& o, std::ostream& out) {
  StepErrorTimingResult timing;
  fs::path timing_file;
  try {
    const fs::path job_file = o.experiment_file("step_error/table8_timing.yaml");
    if (!fs::exists(job_file)) throw MissingResults(job_file.string() + ": not found");
    const StepErrorTimingJob job = load_step_error_timing_job(job_file, {}, o.profile);
    const StoredResult stored = table_store(o).get(step_error_timing_key(job));
    timing_file = stored.file;
    timing = read_step_error_timing(stored.record, stored.file);
  } catch (const MissingResults& e) {
    const std::string why = "(Seed 000 Table 8 not printed: " + std::string(e.what()) + ")";
    if (o.format == TableFormat::csv || o.format == TableFormat::json) {
      print_table_notes(out, o.format, {why});  // a comment or note, not a row
    } else {
      out << "\n" << why << "\n";
    }
    return;
  }
  std::map<std::string, const SurfaceTiming*> by;
  for (const auto& t : timing.surfaces) by[t.surface] = &t;
  for (const char* surface : {"surface2", "surface3"}) {
    if (!by.count(surface)) throw Error("Table 8 timing result lacks " + std::string(surface));
  }
  const SurfaceTiming& t2 = *by.at("surface2");
  const SurfaceTiming& t3 = *by.at("surface3");
  // Rows are quantities, seconds or ratios: csv/json carry the unit in each
  // row's key (planning_s, ratio_network_total_to_geometric).
  TypedTable t;
  t.columns = {label_column("Method", "method"), number_column("Surface 2 (s) ours", "surface2"),
               number_column("paper", "surface2_paper"),
               number_column("Surface 3 (s) ours", "surface3"),
               number_column("paper", "surface3_paper")};
  const auto sec = [](double v) { return number_cell(v, table_number(v, 4)); };
  const auto row = [&](const std::string& label, const std::string& key,
                       double SurfaceTiming::*field, const std::map<std::string, double>* paper) {
    t.rows.push_back({label_cell(label, key), sec(t2.*field),
                      paper ? sec(paper->at("surface2")) : missing_cell("-"), sec(t3.*field),
                      paper ? sec(paper->at("surface3")) : missing_cell("-")});
  };
  row("tool-path planning (shared start of all three)", "planning_s", &SurfaceTiming::planning_s,
      nullptr);
  row("(a) geometric method (iterative)", "geometric_s", &SurfaceTiming::iterative_s,
      &s.ref.table8_geometric);
  row("(b) exact method (ours)", "exact_s", &SurfaceTiming::exact_s, nullptr);
  row("(c) network: load model from result file", "network_load_s", &SurfaceTiming::network_load_s,
      nullptr);
  row("(c) network: inputs from the tool path", "network_inputs_s",
      &SurfaceTiming::network_inputs_s, nullptr);
  row("(c) network: normalise + forward pass", "network_forward_s",
      &SurfaceTiming::network_forward_s, nullptr);
  t.rows.push_back({label_cell("(c) network total (\"proposed method\")", "network_total_s"),
                    sec(t2.network_total_s()), sec(s.ref.table8_proposed.at("surface2")),
                    sec(t3.network_total_s()), sec(s.ref.table8_proposed.at("surface3"))});
  const auto ratio = [](double a, double b) { return number_cell(a / b, table_number(a / b, 3)); };
  t.rows.push_back(
      {label_cell("ratio network total / geometric", "ratio_network_total_to_geometric"),
       ratio(t2.network_total_s(), t2.iterative_s),
       ratio(s.ref.table8_proposed.at("surface2"), s.ref.table8_geometric.at("surface2")),
       ratio(t3.network_total_s(), t3.iterative_s),
       ratio(s.ref.table8_proposed.at("surface3"), s.ref.table8_geometric.at("surface3"))});
  t.rows.push_back(
      {label_cell("ratio network load + forward / geometric",
                  "ratio_network_load_forward_to_geometric"),
       ratio(t2.network_load_s + t2.network_forward_s, t2.iterative_s), missing_cell("-"),
       ratio(t3.network_load_s + t3.network_forward_s, t3.iterative_s), missing_cell("-")});
  const TableFormat format = o.format;
  print_table_title(out, format,
                    "Seed 000 Table 8: time to obtain the step errors of the surface-2 and "
                    "surface-3 test sets (15 % fine-tuning; " +
                        std::to_string(t2.test_samples) + " and " +
                        std::to_string(t3.test_samples) + " samples)");
  t.print(out, format);
  const auto verdict = [](const SurfaceTiming& x, const std::string& name) {
    const double r = x.network_total_s() / x.iterative_s;
    return name + ": the network end to end is " +
           (r < 1 ? table_number(1 / r, 3) + "x faster than"
                  : table_number(r, 3) + "x slower than") +
           " the iterative geometric method and " +
           table_number(x.network_total_s() / x.exact_s, 3) + "x the exact method's time.";
  };
  print_table_notes(
      out, format,
      {verdict(t2, "Surface 2"), verdict(t3, "Surface 3"),
       "Measured in one run by " + timing.name +
           (o.profile.empty() ? std::string(" (no profile)") : " (profile " + o.profile + ")") +
           " on " + timing.host + " (" + timing.utc + ", cnclab " + timing.cnclab_version + ", " +
           timing.git_commit +
           "), single thread, "
           "median of " +
           std::to_string(timing.repeats) +
           " repeat(s). The paper: i7-12700KF, RTX 3070 Ti, PyTorch (other hardware and software).",
       "All three start from the same planned tool-path lines (CC curve, CC and CL points), "
       "timed once on the first row. The paper's network read precomputed samples (its time "
       "includes loading the model only), so 'load model' + 'forward pass' is the figure "
       "comparable with its " +
           table_number(s.ref.table8_proposed.at("surface2")) + " / " +
           table_number(s.ref.table8_proposed.at("surface3")) +
           " s; 'network total' adds computing the 73 inputs from the tool path, the same start "
           "as the geometric methods.",
       "Accuracy against the exact value: iterative max |e| " +
           table_number(t2.iterative_max_error_um, 3) + " / " +
           table_number(t3.iterative_max_error_um, 3) + " µm, network max |e| " +
           table_number(t2.network_max_error_um, 3) + " / " +
           table_number(t3.network_max_error_um, 3) + " µm (surface 2 / 3)."});
  print_table_sources(out, format, {s.reference_file, timing_file});
}

}  // namespace cnclab
