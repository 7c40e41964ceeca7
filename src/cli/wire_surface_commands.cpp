// CLI11 wiring of `cnclab surface show/export/example-part` (cli_wiring.hpp);
// the work is in cad/ (surface_files.hpp, cad_faces.hpp) and
// report/cad_part_report.hpp.
#include <cstdio>
#include <iostream>
#include <memory>

#include "cli/cli_wiring.hpp"
#include "cnclab/cad/cad_faces.hpp"
#include "cnclab/cad/surface_files.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/report/cad_part_report.hpp"

namespace cnclab {

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
    action = [a] {
      const CadShowOptions o = show_options(*a);
      print_cad_part(a->file, summarise_cad_part(a->file, o), o.path, a->why, std::cout);
      return 0;
    };
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
      std::cerr << export_surface_file(e->source, e->face, read, e->out) << "\n";
      return 0;
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
    action = [p] {
      std::cerr << write_example_part(p->source, p->out) << "\n";
      return 0;
    };
  });
}

}  // namespace cnclab
