#pragma once
// The trochoidal groove G-code job (seed 004 Sec. 3, Tables 2-3): a
// non-training experiment (`kind: gcode`) that makes the tool path, writes
// the ISO 6983 program and reports the point table (Table 3's layout), the
// radial engagement against slotting, and how Table 3 relates to Eq. 6.
//
// YAML (experiments/trochoid/groove_table2.yaml):
//   kind: gcode
//   name: trochoid_groove_table2
//   description: ...
//   toolpath: trochoid            # the only path type so far
//   trochoid: {cutter_diameter, groove_width, groove_length, step, chord_tolerance}
//   program: {program_number, title, feed, plunge_feed, spindle_speed, safe_z, cut_z,
//             line_increment, decimals}
//   entry: {mode: helix | outside, ramp_angle: 3, clearance: 1}   (kinematics/tool_entry.hpp)
//   report: {table_rows, engagement_spacing, engagement_every,
//            compare_with: results/reference/trochoid_table3.csv}
#include <cstddef>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/core/fields.hpp"
#include "cnclab/experiment/job_result.hpp"
#include "cnclab/experiment/result_store.hpp"
#include "cnclab/kinematics/gcode.hpp"
#include "cnclab/kinematics/tool_entry.hpp"
#include "cnclab/kinematics/trochoid.hpp"

namespace cnclab {

struct TrochoidReportOptions {
  std::size_t table_rows = 12;  // point-table rows printed (Table 3 shows 12); all go to the file
  double engagement_spacing = 0.05;  // path resampling for the engagement [mm]: overestimate
                                     // <= 2 asin(s / D) (0.29 deg for s = 0.05, D = 20)
  double engagement_every = 0.5;     // evaluate the engagement every this much path [mm]
  // Table 3 transcribed (CSV: t,x,y,line,coordinates), relative to the
  // working directory; absent = no comparison.
  std::optional<std::filesystem::path> compare_with;
  void validate() const;
};

struct TrochoidJob {
  std::string name;  // file-name-safe; outputs results/<name>/<name>.nc etc.
  std::string description;
  TrochoidGrooveOptions groove;
  GcodeOptions program;
  EntryOptions entry;
  TrochoidReportOptions report;
  std::filesystem::path source_file;
  JobRequest request;  // the command's overrides and --profile (provenance only)
};

// The declared keys of a `kind: gcode` file below its kind, name,
// description and toolpath: trochoid, program, entry, report.
const FieldList<TrochoidJob>& trochoid_job_fields();
// Every key of a gcode file, for its schema: kind, name, description,
// toolpath, then the sections above.
std::vector<FieldInfo> trochoid_file_fields();

// Reads a `kind: gcode` file strictly (unknown keys are errors), applying
// the profile (core/config.hpp), then `key=value` overrides, first.
TrochoidJob load_trochoid_job(const std::filesystem::path& file,
                              const std::vector<std::string>& overrides = {},
                              const std::string& profile = {});

// The resolved job, defaults included, as YAML that loads back to the same
// job (what `cnclab validate` prints).
std::string to_yaml(const TrochoidJob& job);

struct TrochoidOutcome {
  TrochoidGroove groove;
  GcodeProgram program;
  ToolEntry entry;
  double ramp_engagement_rad = 0;   // the entry's feed moves (in the plane)
  double max_engagement_rad = 0;    // steady state: the N loops
  double entry_engagement_rad = 0;  // start circle, after the entry
  double exit_engagement_rad = 0;   // end circle
  std::string point_table;          // the full point table (TSV)
  std::string report;               // what is printed
};

// Computes everything; writes nothing.
TrochoidOutcome run_trochoid_job(const TrochoidJob& job);

struct TrochoidFiles {
  std::filesystem::path program;  // results/<name>/<name>.nc
  std::filesystem::path result;   // the standard result naming the outputs
  TrochoidOutcome outcome;
};

// The result's identity: the job's name and resolved YAML.
ResultKey trochoid_key(const TrochoidJob& job);

// Runs the job and writes results/<name>/<name>.nc, <name>-points.tsv and
// <name>-report.txt, then the standard result (experiment/job_result.hpp,
// kind gcode; metrics points, program_lines, loops, radius_mm, advance_mm,
// {max,entry,exit}_engagement_deg; outputs program, points, report) at the
// result store's path for trochoid_key, each atomically (what `run` and
// `reproduce` do).
TrochoidFiles write_trochoid_outputs(const TrochoidJob& job,
                                     const std::filesystem::path& results_dir);

}  // namespace cnclab
