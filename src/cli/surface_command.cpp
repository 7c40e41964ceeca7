#include "cli/surface_command.hpp"

#include <iostream>
#include <memory>

#include "cli/cli_wiring.hpp"
#include "cnclab/cad/cad_export.hpp"
#include "cnclab/cad/cad_faces.hpp"
#include "cnclab/core/config.hpp"
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

std::string surface_range_text(double a, double b) {
  return "[" + table_number(a, 6) + ", " + table_number(b, 6) + "]";
}

std::string surface_point_text(const Eigen::Vector3d& p) {
  return "(" + table_number(p.x(), 5) + ", " + table_number(p.y(), 5) + ", " +
         table_number(p.z(), 5) + ")";
}

}  // namespace

int surface_show_command(const fs::path& file, std::ostream& out) {
  const std::vector<CadFaceSummary> faces = list_cad_faces(file);
  TextTable t;
  t.header = {"face", "type", "degrees", "u", "v", "area [mm²]", "box min [mm]", "box max [mm]"};
  for (const CadFaceSummary& f : faces) {
    t.rows.push_back({std::to_string(f.index), f.surface_type,
                      f.degree_u ? std::to_string(f.degree_u) + " x " + std::to_string(f.degree_v)
                                 : kMissingCell,
                      surface_range_text(f.u0, f.u1), surface_range_text(f.v0, f.v1),
                      table_number(f.area, 6), surface_point_text(f.box_min),
                      surface_point_text(f.box_max)});
  }
  out << file.string() << ": " << faces.size() << " face" << (faces.size() == 1 ? "" : "s")
      << " (use one as surface: {file: " << file.filename().string() << ", face: N})\n";
  t.print_aligned(out);
  return 0;
}

int surface_export_command(const fs::path& surface_yaml, const fs::path& out_file,
                           std::ostream& log) {
  const CadFormat format = require_cad_format(out_file);
  const NurbsSurface s = load_surface_yaml(surface_yaml);
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

void add_surface_commands(CLI::App& app, CommandAction& action) {
  auto* surface = app.add_subcommand("surface", "Inspect STEP/IGES faces; export YAML surfaces");
  surface->require_subcommand(1);
  auto file = std::make_shared<std::string>();
  auto* show = surface->add_subcommand(
      "show", "List the faces of a STEP/IGES file: type, degrees, bounds, area, bounding box");
  show->add_option("file", *file, "STEP (.step, .stp) or IGES (.iges, .igs) file")->required();
  show->footer("Example:\n  cnclab surface show experiments/step_error/cad_example_part.step");
  show->callback(
      [file, &action] { action = [file] { return surface_show_command(*file, std::cout); }; });
  struct ExportArgs {
    std::string surface, out;
  };
  auto e = std::make_shared<ExportArgs>();
  auto* exp = surface->add_subcommand(
      "export", "Write a YAML NURBS surface as a STEP or IGES B-spline face (atomically)");
  exp->add_option("surface", e->surface, "Surface YAML (configs/surfaces/*.yaml layout)")
      ->required()
      ->check(CLI::ExistingFile);
  exp->add_option("--out,-o", e->out, "File to write: .step, .stp, .iges or .igs")->required();
  exp->footer("Example:\n  cnclab surface export configs/surfaces/surface1.yaml --out s1.step");
  exp->callback([e, &action] {
    action = [e] { return surface_export_command(e->surface, e->out, std::cerr); };
  });
  auto p = std::make_shared<ExportArgs>();
  p->surface = "configs/surfaces/surface1.yaml";
  auto* part = surface->add_subcommand(
      "example-part", "Write the 4-face example part of experiments/step_error/cad_example.yaml");
  part->add_option("--freeform", p->surface, "Surface YAML of face 1")
      ->capture_default_str()
      ->check(CLI::ExistingFile);
  part->add_option("--out,-o", p->out, "File to write: .step, .stp, .iges or .igs")->required();
  part->footer(
      "Example:\n  cnclab surface example-part --out experiments/step_error/cad_example_part.step");
  part->callback([p, &action] {
    action = [p] { return surface_example_part_command(p->surface, p->out, std::cerr); };
  });
}

}  // namespace cnclab
