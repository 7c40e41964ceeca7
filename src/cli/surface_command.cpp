#include "cli/surface_command.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "cli/cli_wiring.hpp"
#include "cnclab/cad/cad_export.hpp"
#include "cnclab/cad/cad_faces.hpp"
#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/geometry/surface_config.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/report/text_table.hpp"

namespace cnclab {
namespace fs = std::filesystem;

namespace {

NurbsSurface load_surface_yaml(const fs::path& file) {
  ConfigDocument doc = ConfigDocument::load(file);
  NurbsSurface s = read_nurbs_surface(doc.root());
  doc.check_all_consumed();
  return s;
}

std::string surface_point_text(const Eigen::Vector3d& p) {
  return "(" + table_number(p.x(), 5) + ", " + table_number(p.y(), 5) + ", " +
         table_number(p.z(), 5) + ")";
}

std::string range_text(double a, double b) {
  if (std::isnan(a)) return kMissingCell;
  return "[" + table_number(a, 3) + ", " + table_number(b, 3) + "]";
}

std::string radius_text(const CadFaceSummary& f) {
  if (std::isinf(f.min_radius)) return "∞ (flat)";
  return table_number(f.min_radius, 4) + (f.min_radius_concave ? " concave" : " convex");
}

std::string verdict_text(const std::string& usable) {
  return usable == "yes" ? usable : "no: " + usable;
}

std::string share_text(const CadFaceSummary& f) {
  if (f.clip_share < 0) return verdict_text(f.clip_usable);
  return table_number(100.0 * f.clip_share, 3) + " %";
}

bool is_millimetre(const std::string& unit) {
  return unit == "mm" || unit == "millimetre" || unit == "millimeter";
}

}  // namespace

int surface_show_command(const fs::path& file, const CadShowOptions& options, bool why,
                         std::ostream& out) {
  const CadPartSummary part = summarise_cad_part(file, options);
  const ToolPathOptions& o = options.path;
  const Eigen::Vector3d axis = o.unit_tool_axis();
  out << file.string() << ": " << part.faces.size() << " face"
      << (part.faces.size() == 1 ? "" : "s") << "; unit "
      << (part.unit.empty() ? "not declared" : part.unit)
      << (is_millimetre(part.unit) ? "" : " (converted: lengths below are in mm)")
      << "; written by " << (part.writer.empty() ? "(not given)" : part.writer) << "\n"
      << "use one as surface: {file: " << file.filename().string() << ", face: N}\n"
      << "verdicts on a " << o.lines << " x " << o.points_per_line
      << " probe path: R = " << table_number(o.tool_radius, 6) << " mm, feed along "
      << (o.feed == FeedDirection::u ? "u" : "v") << ", tool axis " << surface_point_text(axis)
      << ", max normal angle " << table_number(o.max_normal_angle, 4)
      << " deg; n·axis: the normal on the tool side; clip: the path's share left with "
         "unreachable: clip\n";
  TextTable t;
  t.header = {"face",       "type",         "degrees",         "trimmed", "holes",
              "solid",      "n·axis",       "min radius [mm]", "usable",  "clip",
              "area [mm²]", "box min [mm]", "box max [mm]"};
  for (const CadFaceSummary& f : part.faces) {
    t.rows.push_back({std::to_string(f.index), f.surface_type,
                      f.degree_u ? std::to_string(f.degree_u) + " x " + std::to_string(f.degree_v)
                                 : kMissingCell,
                      f.trimmed ? "yes" : "no", std::to_string(f.holes), f.of_solid ? "yes" : "no",
                      range_text(f.axis_min, f.axis_max), radius_text(f), verdict_text(f.usable),
                      share_text(f), table_number(f.area, 6), surface_point_text(f.box_min),
                      surface_point_text(f.box_max)});
  }
  t.print_aligned(out);
  if (why) {
    for (const CadFaceSummary& f : part.faces) {
      if (!f.reason_text.empty()) out << f.reason_text << "\n";
    }
  }
  return 0;
}

int surface_export_command(const fs::path& source, int face, const CadReadOptions& read,
                           const fs::path& out_file, std::ostream& log) {
  const CadFormat format = require_cad_format(out_file);
  if (cad_format_of(source)) {
    if (face < 1) {
      throw ConfigError(source.string() +
                        ": a CAD file's face to export is needed: --face N (faces count from 1; "
                        "`cnclab surface show " +
                        source.string() + "` lists them)");
    }
    const CadPart part = read_cad_part(source, read);
    write_text_atomically(out_file, cad_face_text(part, face, format));
    const CadSurface cad = part.face(face);
    log << "wrote " << out_file.string() << " (face " << face << " of " << source.string() << ": a "
        << cad.surface_type << " as a NURBS face, degrees " << cad.surface.degree_u << " x "
        << cad.surface.degree_v << ", " << (cad.trimmed ? "trimmed" : "untrimmed") << ", "
        << cad.holes << " hole" << (cad.holes == 1 ? "" : "s") << ")\n";
    return 0;
  }
  if (face != 0) {
    throw ConfigError(source.string() + ": --face applies to STEP/IGES files, not a YAML surface");
  }
  const NurbsSurface s = load_surface_yaml(source);
  write_text_atomically(out_file, cad_surface_text(s, format));
  log << "wrote " << out_file.string() << " (one B-spline face, degrees " << s.degree_u << " x "
      << s.degree_v << ", " << s.count_u << " x " << s.count_v << " control points)\n";
  return 0;
}

int surface_example_part_command(const fs::path& freeform_yaml, const fs::path& out_file,
                                 std::ostream& log) {
  const CadFormat format = require_cad_format(out_file);
  write_text_atomically(out_file, cad_example_part_text(load_surface_yaml(freeform_yaml), format));
  log << "wrote " << out_file.string() << " (4 faces: bspline, cylinder, plane, sphere)\n";
  return 0;
}

namespace {

struct ShowArgs {
  std::string file, path = "50x50", feed = "u";
  double tool_radius = 5.0, max_normal_angle = 85.0;
  std::vector<double> tool_axis = {0.0, 0.0, 1.0};
  double read_timeout = 0;
  bool why = false;
};

CadShowOptions show_options(const ShowArgs& a) {
  CadShowOptions o;
  o.read.read_timeout = a.read_timeout;
  std::size_t lines = 0, points = 0;
  char end = 0;
  if (std::sscanf(a.path.c_str(), "%zux%zu%c", &lines, &points, &end) != 2) {
    throw ConfigError("--path " + a.path + ": expected LINESxPOINTS, e.g. 50x50");
  }
  o.path.lines = lines;
  o.path.points_per_line = points;
  o.path.tool_radius = a.tool_radius;
  o.path.max_normal_angle = a.max_normal_angle;
  o.path.tool_axis = a.tool_axis;
  if (a.feed != "u" && a.feed != "v") throw ConfigError("--feed " + a.feed + ": expected u or v");
  o.path.feed = a.feed == "u" ? FeedDirection::u : FeedDirection::v;
  try {
    o.read.validate();
    o.path.validate();
  } catch (const OptionError& e) {
    throw ConfigError("--" + e.field() + ": " + e.what());
  }
  return o;
}

}  // namespace

void add_surface_commands(CLI::App& app, CommandAction& action) {
  auto* surface =
      app.add_subcommand("surface", "Inspect STEP/IGES faces; export YAML surfaces and CAD faces");
  surface->require_subcommand(1);
  auto a = std::make_shared<ShowArgs>();
  auto* show = surface->add_subcommand(
      "show",
      "List the faces of a STEP/IGES file: type, trims, holes, normal along the tool axis, "
      "smallest radius of curvature, and whether a tool path is possible as is or why not");
  show->add_option("file", a->file, "STEP (.step, .stp) or IGES (.iges, .igs) file")->required();
  show->add_option("--path", a->path, "Probe tool path LINESxPOINTS of the verdicts")
      ->capture_default_str();
  show->add_option("--tool-radius", a->tool_radius, "Ball radius R [mm]")->capture_default_str();
  show->add_option("--tool-axis", a->tool_axis, "Tool axis x,y,z")
      ->delimiter(',')
      ->expected(3)
      ->capture_default_str();
  show->add_option("--feed", a->feed, "Feed along u or v")->capture_default_str();
  show->add_option("--max-normal-angle", a->max_normal_angle,
                   "Largest angle [deg] of the normal from the tool axis")
      ->capture_default_str();
  show->add_option("--read-timeout", a->read_timeout,
                   "Seconds the reader may take (0: 60 + 10 per MB)")
      ->capture_default_str();
  show->add_flag("--why", a->why, "Print each refused face's reason (face, line, CC point)");
  show->footer(
      "Example:\n  cnclab surface show experiments/step_error/cad_example_part.step\n  cnclab "
      "surface show part.step --tool-radius 2 --tool-axis 1,0,0 --why");
  show->callback([a, &action] {
    action = [a] { return surface_show_command(a->file, show_options(*a), a->why, std::cout); };
  });
  struct ExportArgs {
    std::string source, out;
    int face = 0;
    double read_timeout = 0;
  };
  auto e = std::make_shared<ExportArgs>();
  auto* exp = surface->add_subcommand(
      "export",
      "Write a YAML NURBS surface, or one face of a STEP/IGES file with its trims, as a STEP or "
      "IGES NURBS face (atomically)");
  exp->add_option("source", e->source,
                  "Surface YAML (configs/surfaces/*.yaml layout) or STEP/IGES file")
      ->required()
      ->check(CLI::ExistingFile);
  exp->add_option("--face", e->face, "The face of a STEP/IGES source (from 1)");
  exp->add_option("--out,-o", e->out, "File to write: .step, .stp, .iges or .igs")->required();
  exp->add_option("--read-timeout", e->read_timeout,
                  "Seconds the reader may take (0: 60 + 10 per MB)");
  exp->footer(
      "Example:\n  cnclab surface export configs/surfaces/surface1.yaml --out s1.step\n  cnclab "
      "surface export part.step --face 3 --out face3.igs");
  exp->callback([e, &action] {
    action = [e] {
      CadReadOptions read;
      read.read_timeout = e->read_timeout;
      try {
        read.validate();
      } catch (const OptionError& error) {
        throw ConfigError("--read-timeout: " + std::string(error.what()));
      }
      return surface_export_command(e->source, e->face, read, e->out, std::cerr);
    };
  });
  auto p = std::make_shared<ExportArgs>();
  p->source = "configs/surfaces/surface1.yaml";
  auto* part = surface->add_subcommand(
      "example-part", "Write the 4-face example part of experiments/step_error/cad_example.yaml");
  part->add_option("--freeform", p->source, "Surface YAML of face 1")
      ->capture_default_str()
      ->check(CLI::ExistingFile);
  part->add_option("--out,-o", p->out, "File to write: .step, .stp, .iges or .igs")->required();
  part->footer(
      "Example:\n  cnclab surface example-part --out experiments/step_error/cad_example_part.step");
  part->callback([p, &action] {
    action = [p] { return surface_example_part_command(p->source, p->out, std::cerr); };
  });
}

}  // namespace cnclab
