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
#include "cnclab/core/units.hpp"
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

EntryOptions read_entry(const ConfigReader& r) {
  EntryOptions e;
  const auto mode = r.get<std::string>("mode", to_string(e.mode));
  if (mode != "helix" && mode != "outside") r.fail("mode", "must be one of: helix, outside");
  e.mode = mode == "helix" ? EntryMode::helix : EntryMode::outside;
  e.ramp_angle = r.get<double>("ramp_angle", e.ramp_angle);
  e.clearance = r.get<double>("clearance", e.clearance);
  r.validate([&] { e.validate(); });
  return e;
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

TrochoidJob load_trochoid_job(const fs::path& file, const std::vector<std::string>& overrides,
                              const std::string& profile) {
  ConfigDocument doc = ConfigDocument::load(file, profile);
  for (const auto& text : overrides) doc.apply(parse_override(text));
  const ConfigReader root = doc.root();
  if (root.get<std::string>("kind", "gcode") != "gcode") root.fail("kind", "must be gcode");
  TrochoidJob job;
  job.source_file = file;
  job.name = read_experiment_name(root);
  job.description = root.get<std::string>("description", "");
  if (root.get<std::string>("toolpath", "trochoid") != "trochoid") {
    root.fail("toolpath", "must be one of: trochoid");
  }

  const ConfigReader g = root.section("trochoid");
  TrochoidGrooveOptions& o = job.groove;
  o.cutter_diameter = g.get<double>("cutter_diameter", o.cutter_diameter);
  o.groove_width = g.get<double>("groove_width", o.groove_width);
  o.groove_length = g.get<double>("groove_length", o.groove_length);
  o.step = g.get<double>("step", o.step);
  o.chord_tolerance = g.get<double>("chord_tolerance", o.chord_tolerance);
  g.validate([&] { o.validate(); });

  const ConfigReader p = root.section("program");
  GcodeOptions& c = job.program;
  c.program_number = static_cast<int>(p.get<std::int64_t>("program_number", c.program_number));
  c.title = p.get<std::string>("title", c.title);
  c.feed = p.get<double>("feed", c.feed);
  c.plunge_feed = p.get<double>("plunge_feed", c.plunge_feed);
  c.spindle_speed = p.get<double>("spindle_speed", c.spindle_speed);
  c.safe_z = p.get<double>("safe_z", c.safe_z);
  c.cut_z = p.get<double>("cut_z", c.cut_z);
  c.line_increment = static_cast<int>(p.get<std::int64_t>("line_increment", c.line_increment));
  c.decimals = static_cast<int>(p.get<std::int64_t>("decimals", c.decimals));
  p.validate([&] { c.validate(); });

  job.entry = read_entry(root.section("entry"));

  const ConfigReader r = root.section("report");
  TrochoidReportOptions& rep = job.report;
  rep.table_rows = r.get<std::size_t>("table_rows", rep.table_rows);
  rep.engagement_spacing = r.get<double>("engagement_spacing", rep.engagement_spacing);
  rep.engagement_every = r.get<double>("engagement_every", rep.engagement_every);
  if (const auto path = r.optional<std::string>("compare_with")) rep.compare_with = *path;
  r.validate([&] { rep.validate(); });
  doc.check_all_consumed();
  return job;
}

std::string to_yaml(const TrochoidJob& job) {
  using YAML::Key, YAML::Value, YAML::BeginMap, YAML::EndMap;
  YAML::Emitter out;
  out << BeginMap << Key << "kind" << Value << "gcode" << Key << "name" << Value << job.name << Key
      << "description" << Value << job.description << Key << "toolpath" << Value << "trochoid";
  const auto& g = job.groove;
  out << Key << "trochoid" << Value << BeginMap;
  out << Key << "cutter_diameter" << Value << shortest_double(g.cutter_diameter);
  out << Key << "groove_width" << Value << shortest_double(g.groove_width);
  out << Key << "groove_length" << Value << shortest_double(g.groove_length);
  out << Key << "step" << Value << shortest_double(g.step);
  out << Key << "chord_tolerance" << Value << shortest_double(g.chord_tolerance) << EndMap;
  const auto& p = job.program;
  out << Key << "program" << Value << BeginMap;
  out << Key << "program_number" << Value << p.program_number;
  out << Key << "title" << Value << p.title;
  out << Key << "feed" << Value << shortest_double(p.feed);
  out << Key << "plunge_feed" << Value << shortest_double(p.plunge_feed);
  out << Key << "spindle_speed" << Value << shortest_double(p.spindle_speed);
  out << Key << "safe_z" << Value << shortest_double(p.safe_z);
  out << Key << "cut_z" << Value << shortest_double(p.cut_z);
  out << Key << "line_increment" << Value << p.line_increment;
  out << Key << "decimals" << Value << p.decimals << EndMap;
  out << Key << "entry" << Value << BeginMap;
  out << Key << "mode" << Value << to_string(job.entry.mode);
  out << Key << "ramp_angle" << Value << shortest_double(job.entry.ramp_angle);
  out << Key << "clearance" << Value << shortest_double(job.entry.clearance) << EndMap;
  const auto& r = job.report;
  out << Key << "report" << Value << BeginMap;
  out << Key << "table_rows" << Value << r.table_rows;
  out << Key << "engagement_spacing" << Value << shortest_double(r.engagement_spacing);
  out << Key << "engagement_every" << Value << shortest_double(r.engagement_every);
  if (r.compare_with) out << Key << "compare_with" << Value << r.compare_with->string();
  out << EndMap << EndMap;
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
  if (job.report.compare_with) compare_with_table3(*job.report.compare_with, g.radius, out);
  res.report = out.str();
  return res;
}

ResultKey trochoid_key(const TrochoidJob& job) {
  return {job.name, std::nullopt, to_yaml(job), job.source_file, false};
}

TrochoidFiles write_trochoid_outputs(const TrochoidJob& job, const fs::path& results_dir) {
  const ResultKey key = trochoid_key(job);
  RunRecord rec = make_job_record("gcode", key);
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
  rec.provenance.end_utc = utc_now_iso8601();
  rec.provenance.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_job_result(files.result, rec);  // last: it names the files above
  return files;
}

}  // namespace cnclab
