#include "cnclab/studies/five_axis/trochoid_job.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/share_paths.hpp"
#include "cnclab/core/units.hpp"
#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/experiment/job_result.hpp"
#include "cnclab/experiment/spec.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/io/provenance.hpp"
#include "cnclab/kinematics/engagement.hpp"
#include "cnclab/report/text_table.hpp"
#include "cnclab/studies/five_axis/trochoid_table3.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

const FieldList<TrochoidGrooveOptions>& groove_fields() {
  using G = TrochoidGrooveOptions;
  static const auto fields =
      FieldList<G>()
          .field("cutter_diameter", &G::cutter_diameter, "D [mm] (seed 004 Table 2: 20)",
                 Rule::positive())
          .field("groove_width", &G::groove_width, "W [mm], > D (Table 2: 28)", Rule::positive())
          .field("groove_length", &G::groove_length, "L [mm], >= W (Table 2: 120)",
                 Rule::positive())
          .field("step", &G::step, "largest advance per loop [mm], <= W - D (Table 2: 1.5)",
                 Rule::positive())
          .field("chord_tolerance", &G::chord_tolerance,
                 "largest deviation of a G01 chord from Eq. 6 [mm], < (W - D)/2", Rule::positive());
  return fields;
}

const FieldList<GcodeOptions>& program_fields() {
  using C = GcodeOptions;
  static const auto fields =
      FieldList<C>()
          .field("program_number", &C::program_number, "O-word", Rule::in(1, true, 9999, true))
          .field("title", &C::title, "comment after the O-word (no parentheses)")
          .field("feed", &C::feed, "G01 feed in the plane [mm/min]", Rule::positive())
          .field("plunge_feed", &C::plunge_feed, "G01 feed of the entry moves [mm/min]",
                 Rule::positive())
          .field("spindle_speed", &C::spindle_speed, "S-word [rpm]", Rule::positive())
          .field("safe_z", &C::safe_z, "retract height above the part top (z = 0) [mm]",
                 Rule::finite_number())
          .field("cut_z", &C::cut_z, "cutting depth [mm], below safe_z", Rule::finite_number())
          .field("line_increment", &C::line_increment, "N-word step", Rule::at_least(1))
          .field("decimals", &C::decimals, "coordinate decimals", Rule::in(0, true, 6, true));
  return fields;
}

const FieldList<EntryOptions>& entry_fields() {
  using E = EntryOptions;
  static const auto fields =
      FieldList<E>()
          .choice("mode", &E::mode, {{"helix", EntryMode::helix}, {"outside", EntryMode::outside}},
                  "helix: helical ramp about the start circle; outside: straight in from "
                  "outside the stock (an open groove end)")
          .field("ramp_angle", &E::ramp_angle, "helix descent angle [deg]",
                 Rule::in(0, false, 45, true))
          .field("clearance", &E::clearance,
                 "helix: ramp start above the stock top; outside: from the edge [mm]",
                 Rule::positive());
  return fields;
}

const FieldList<TrochoidReportOptions>& report_fields() {
  using R = TrochoidReportOptions;
  static const auto fields =
      FieldList<R>()
          .field("table_rows", &R::table_rows, "point-table rows printed (Table 3 shows 12)")
          .field("engagement_spacing", &R::engagement_spacing,
                 "path resampling for the engagement [mm]", Rule::positive())
          .field("engagement_every", &R::engagement_every,
                 "evaluate the engagement every this much path [mm], >= engagement_spacing",
                 Rule::positive())
          .custom(
              custom_info("compare_with",
                          "Table 3 transcribed (CSV), relative to the working directory "
                          "or else to cnclab's share folder (results/reference/...); "
                          "absent: no comparison",
                          FieldKind::string),
              [](const ConfigReader& r, R& rep) {
                if (const auto path = r.optional<std::string>("compare_with")) {
                  rep.compare_with = *path;
                }
              },
              [](const R& rep) {
                return rep.compare_with ? YAML::Node(rep.compare_with->string()) : YAML::Node();
              },
              [](const R& rep) { return rep.compare_with.has_value(); });
  return fields;
}

std::string entry_report(const TrochoidJob& job, const TrochoidOutcome& res) {
  std::ostringstream out;
  const ToolEntry& e = res.entry;
  const std::string depth = shortest_double(job.program.cut_z);
  const std::string engaged = fixed_decimals(res.ramp_engagement_rad * kDegPerRad, 1) + " deg";
  if (e.mode == EntryMode::helix) {
    out << "  entry: helical ramp at " << shortest_double(job.entry.ramp_angle)
        << " deg about the start circle (R " << shortest_double(res.groove.radius) << " mm), "
        << fixed_decimals(e.revolutions, 2) << " turns of "
        << fixed_decimals(e.depth_per_revolution, 3) << " mm from z "
        << shortest_double(job.entry.clearance) << " to " << depth << " mm\n"
        << "    on the ramp (each turn cuts a new layer): max " << engaged << "\n";
  } else {
    out << "  entry: from outside the stock at x " << fixed_decimals(e.points.front().x(), 3)
        << " mm (the groove must be open at x = 0), straight in along y = 0 at z " << depth
        << " mm\n"
        << "    straight in (plain slotting; the stock edge is not modelled): max " << engaged
        << "\n";
  }
  return out.str();
}
}  // namespace

void TrochoidReportOptions::validate() const {
  if (!(engagement_spacing > 0) || !std::isfinite(engagement_spacing)) {
    throw OptionError("engagement_spacing", shortest_double(engagement_spacing),
                      "must be a finite length > 0 mm");
  }
  if (!(engagement_every >= engagement_spacing) || !std::isfinite(engagement_every)) {
    throw OptionError(
        "engagement_every", shortest_double(engagement_every),
        "must be finite and at least engagement_spacing " + shortest_double(engagement_spacing));
  }
}

const FieldList<TrochoidJob>& trochoid_job_fields() {
  using J = TrochoidJob;
  static const auto fields =
      FieldList<J>()
          .section("trochoid", &J::groove, groove_fields(), "the groove (seed 004 Table 2)")
          .section("program", &J::program, program_fields(), "the G-code program")
          .section("entry", &J::entry, entry_fields(), "how the cutter enters the stock")
          .section("report", &J::report, report_fields(), "the report and Table 3");
  return fields;
}

std::vector<FieldInfo> trochoid_file_fields() {
  std::vector<FieldInfo> fields = job_file_fields("gcode");
  fields.push_back(custom_info("toolpath", "the tool path (default trochoid)", FieldKind::string,
                               Rule::one_of({"trochoid"})));
  for (auto& f : trochoid_job_fields().info()) fields.push_back(std::move(f));
  return fields;
}

TrochoidJob load_trochoid_job(const fs::path& file, const std::vector<std::string>& overrides,
                              const std::string& profile) {
  ConfigDocument doc = ConfigDocument::load(file, profile);
  for (const auto& text : overrides) doc.apply(parse_override(text));
  const ConfigReader root = doc.root();
  if (root.get<std::string>("kind", "gcode") != "gcode") root.fail("kind", "must be gcode");
  TrochoidJob job;
  job.source_file = file;
  job.request = {overrides, profile};
  job.name = read_experiment_name(root);
  job.description = root.get<std::string>("description", "");
  if (root.get<std::string>("toolpath", "trochoid") != "trochoid") {
    root.fail("toolpath", "must be one of: trochoid");
  }

  trochoid_job_fields().read(root, job);
  root.section("trochoid").validate([&] { job.groove.validate(); });
  root.section("program").validate([&] { job.program.validate(); });
  root.section("entry").validate([&] { job.entry.validate(); });
  root.section("report").validate([&] { job.report.validate(); });
  // Across sections: the entry starts at z = clearance above the stock top
  // (z = 0) and must lie below the retract height, and the pass cuts into
  // the stock (kinematics/tool_entry.cpp, gcode.cpp).
  root.section("program").check(job.program.cut_z < 0, "cut_z",
                                "must be below the stock top z = 0");
  root.section("entry").check(
      job.entry.clearance < job.program.safe_z, "clearance",
      "must be below program.safe_z = " + shortest_double(job.program.safe_z) +
          " (the entry starts at z = clearance)");
  doc.check_all_consumed();
  return job;
}

std::string to_yaml(const TrochoidJob& job) {
  using YAML::Key, YAML::Value, YAML::BeginMap, YAML::EndMap;
  YAML::Emitter out;
  out << BeginMap << Key << "kind" << Value << "gcode" << Key << "name" << Value << job.name << Key
      << "description" << Value << job.description << Key << "toolpath" << Value << "trochoid";
  trochoid_job_fields().emit(out, job);
  out << EndMap;
  return std::string(out.c_str()) + "\n";
}

TrochoidOutcome run_trochoid_job(const TrochoidJob& job) {
  TrochoidOutcome res;
  res.groove = make_trochoid_groove(job.groove);
  const TrochoidGroove& g = res.groove;
  res.entry = trochoid_entry(g, job.entry, job.program.cut_z);
  res.program = write_gcode(g.points, job.program, res.entry.points);

  // Point table, Table 3's layout: t, x(t), y(t), line number, coordinates
  // (plus the N-word of the point's block in the program).
  TextTable shown;
  shown.header = {"t", "x(t)", "y(t)", "Line N°", "Block", "Coordinates"};
  res.point_table = "t\tx\ty\tline\tblock\tcoordinates\n";
  for (std::size_t i = 0; i < g.points.size(); ++i) {
    // Appended, not `"N" + std::string`: GCC 12 warns falsely (-Wrestrict, PR105329).
    std::string block = "N";
    block += std::to_string(res.program.point_line_numbers[i]);
    const std::vector<std::string> cells = {fixed_decimals(g.t[i], 4),
                                            fixed_decimals(g.points[i].x(), 4),
                                            fixed_decimals(g.points[i].y(), 4),
                                            std::to_string(i + 1),
                                            block,
                                            coordinate_words(g.points[i], job.program.decimals)};
    if (i < job.report.table_rows) shown.rows.push_back(cells);
    for (std::size_t k = 0; k < cells.size(); ++k) {
      res.point_table += cells[k];
      res.point_table += k + 1 < cells.size() ? '\t' : '\n';
    }
  }

  // Radial engagement along the entry's and the pass's G01 polygon in the
  // plane: the entry's distinct XY points, then the pass's (from its start,
  // where the entry ends).
  std::vector<Eigen::Vector2d> plane;
  for (std::size_t i = 0; i + 1 < res.entry.points.size(); ++i) {
    const Eigen::Vector2d xy = res.entry.points[i].head<2>();
    if (plane.empty() || plane.back() != xy) plane.push_back(xy);
  }
  const std::size_t entry_n = plane.size();
  plane.insert(plane.end(), g.points.begin(), g.points.end());
  std::vector<std::size_t> segment;
  const auto dense = densify(plane, job.report.engagement_spacing, &segment);
  const auto stride = static_cast<std::size_t>(
      std::max(1.0, std::round(job.report.engagement_every / job.report.engagement_spacing)));
  const double tool_radius = job.groove.cutter_diameter / 2;
  const auto engagement = engagement_angles(dense, tool_radius, stride);
  const double t_loops_end = 2 * std::numbers::pi * static_cast<double>(g.loops + 1);
  double steady_sum = 0;
  std::size_t steady_n = 0;
  for (const auto& e : engagement) {
    if (e.index == 0) continue;              // first contact (the 2-D model's full-stock 2 pi)
    const std::size_t i = segment[e.index];  // the segment ends at plane[i]
    if (i <= entry_n) {
      res.ramp_engagement_rad = std::max(res.ramp_engagement_rad, e.angle);
      continue;
    }
    const double t = g.t[i - entry_n];
    if (t <= 2 * std::numbers::pi + 1e-12) {
      res.entry_engagement_rad = std::max(res.entry_engagement_rad, e.angle);
    } else if (t <= t_loops_end + 1e-12) {
      res.max_engagement_rad = std::max(res.max_engagement_rad, e.angle);
      steady_sum += e.angle;
      ++steady_n;
    } else {
      res.exit_engagement_rad = std::max(res.exit_engagement_rad, e.angle);
    }
  }

  std::ostringstream out;
  const auto& o = job.groove;
  out << "Trochoidal groove (seed 004 Table 2): cutter D " << shortest_double(o.cutter_diameter)
      << " mm, groove " << shortest_double(o.groove_width) << " x "
      << shortest_double(o.groove_length) << " mm, step " << shortest_double(o.step)
      << " mm per loop\n"
      << "  trochoid radius R = (W - D)/2 = " << shortest_double(g.radius) << " mm\n"
      << "  centre travel L - W = " << shortest_double(g.centre_travel) << " mm in N = ceil("
      << shortest_double(g.centre_travel) << " / " << shortest_double(o.step) << ") = " << g.loops
      << " loops: advance p = " << fixed_decimals(g.advance, 4) << " mm per loop (<= step)\n"
      << "  Eq. 6 with w = 1 rad per unit t: V = p / (2 pi) = " << fixed_decimals(g.speed, 5)
      << " mm per unit t; plus one full circle at each end\n"
      << "  sampling: " << g.samples_per_loop
      << " points per loop (dt = " << fixed_decimals(g.dt, 5)
      << " rad) for a chord deviation <= " << shortest_double(o.chord_tolerance) << " mm; "
      << g.points.size() << " points, "
      << std::count(res.program.text.begin(), res.program.text.end(), '\n') << " program lines\n";
  out << "\nPoint table (Table 3's layout; first "
      << std::min(job.report.table_rows, g.points.size()) << " of " << g.points.size()
      << " rows; groove frame: x from the groove start, y = 0 on its "
      << "centreline)\n\n";
  shown.print_aligned(out);
  out << "\nRadial engagement (2-D stock removal, exact disc geometry; G01 path resampled every "
      << shortest_double(job.report.engagement_spacing) << " mm, evaluated every "
      << shortest_double(job.report.engagement_every) << " mm)\n"
      << entry_report(job, res) << "  start circle (after the entry):  max "
      << fixed_decimals(res.entry_engagement_rad * kDegPerRad, 1) << " deg\n"
      << "  trochoidal loops:                max "
      << fixed_decimals(res.max_engagement_rad * kDegPerRad, 1) << " deg, mean "
      << fixed_decimals(steady_n ? steady_sum / static_cast<double>(steady_n) * kDegPerRad : 0, 1)
      << " deg\n"
      << "  end circle:                      max "
      << fixed_decimals(res.exit_engagement_rad * kDegPerRad, 1) << " deg\n"
      << "  plain slotting, same cutter:     180 deg (pi + 2 asin(s / D) -> 180 deg as the "
         "resampling s -> 0)\n"
      << "  (resampling overestimates by at most 2 asin(s / D) = "
      << fixed_decimals(
             2 * std::asin(job.report.engagement_spacing / o.cutter_diameter) * kDegPerRad, 2)
      << " deg)\n";
  if (job.report.compare_with) {
    compare_with_table3(require_shared(*job.report.compare_with), g.radius, out);
  }
  res.report = out.str();
  return res;
}

ResultKey trochoid_key(const TrochoidJob& job) {
  return {job.name, std::nullopt, to_yaml(job), job.source_file, false};
}

TrochoidFiles write_trochoid_outputs(const TrochoidJob& job, const fs::path& results_dir) {
  const ResultKey key = trochoid_key(job);
  RunRecord rec = make_job_record("gcode", key, job.request);
  const auto start = std::chrono::steady_clock::now();
  const fs::path dir = results_dir / job.name;
  TrochoidFiles files{dir / (job.name + ".nc"), result_path(key, results_dir),
                      run_trochoid_job(job)};
  const TrochoidOutcome& o = files.outcome;
  rec.outputs = {{"program", job.name + ".nc"},
                 {"points", job.name + "-points.tsv"},
                 {"report", job.name + "-report.txt"}};
  write_text_atomically(files.program, o.program.text);
  write_text_atomically(dir / rec.outputs[1].file, o.point_table);
  write_text_atomically(dir / rec.outputs[2].file, o.report);
  rec.metrics = {{"points", static_cast<double>(o.groove.points.size())},
                 {"program_lines", static_cast<double>(std::count(o.program.text.begin(),
                                                                  o.program.text.end(), '\n'))},
                 {"loops", static_cast<double>(o.groove.loops)},
                 {"radius_mm", o.groove.radius},
                 {"advance_mm", o.groove.advance},
                 {"max_engagement_deg", o.max_engagement_rad * kDegPerRad},
                 {"ramp_engagement_deg", o.ramp_engagement_rad * kDegPerRad},
                 {"start_circle_engagement_deg", o.entry_engagement_rad * kDegPerRad},
                 {"exit_engagement_deg", o.exit_engagement_rad * kDegPerRad}};
  finish_provenance(rec.provenance);
  rec.provenance.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_job_result(files.result, rec);  // last: it names the files above
  return files;
}

}  // namespace cnclab
