#include "cnclab/report/cad_part_report.hpp"

#include <cmath>

#include "cnclab/report/text_table.hpp"

namespace cnclab {
namespace fs = std::filesystem;

namespace {

// Appended, not "(" + ...: GCC 12 warns falsely on that (-Wrestrict, PR105329).
std::string surface_point_text(const Eigen::Vector3d& p) {
  std::string text = "(";
  text += table_number(p.x(), 5) + ", " + table_number(p.y(), 5) + ", " + table_number(p.z(), 5);
  return text + ")";
}

std::string range_text(double a, double b) {
  if (std::isnan(a)) return kMissingCell;
  std::string text = "[";
  text += table_number(a, 3) + ", " + table_number(b, 3);
  return text + "]";
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

void print_cad_part(const fs::path& file, const CadPartSummary& part, const ToolPathOptions& o,
                    bool why, std::ostream& out) {
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
}

}  // namespace cnclab
