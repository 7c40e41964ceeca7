#include "cnclab/data/step_error.hpp"

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/resources.hpp"
#include "cnclab/core/units.hpp"
#include "cnclab/data/declared_generator.hpp"
#include "cnclab/data/named_config_file.hpp"
#include "cnclab/geometry/surface_config.hpp"

namespace cnclab {

namespace {
// Micrometres per millimetre: targets are reported in µm (DESIGN.md "Units").
}  // namespace

void StepErrorDatasetOptions::validate() const {
  surface.validate();
  tool_path.validate();
  exact.validate();
  if (cad) check_tool_path_on_face(*cad, tool_path);
  if (curve_points < 1 || curve_points > 10'000) {
    throw OptionError("curve_points", std::to_string(curve_points), "must be in [1, 10000]");
  }
}

void step_error_inputs(const ToolPathLine& path, std::size_t i, std::size_t k,
                       Eigen::Ref<Eigen::VectorXd> x) {
  const double du = (path.u[i + 1] - path.u[i]) / static_cast<double>(k + 1);
  for (std::size_t j = 0; j < k; ++j) {
    x.segment<3>(static_cast<Eigen::Index>(3 * j)) =
        curve_point(path.curve, path.u[i] + du * static_cast<double>(j + 1));
  }
  const auto base = static_cast<Eigen::Index>(3 * k);
  x.segment<3>(base) = path.cc[i];
  x.segment<3>(base + 3) = path.cc[i + 1];
  x.segment<3>(base + 6) = path.cl[i];
  x.segment<3>(base + 9) = path.cl[i + 1];
  x(base + 12) = path.tool_radius;
}

namespace {

// The dataset of options already validated.
Dataset step_error_dataset_of_valid(const StepErrorDatasetOptions& o) {
  const std::size_t n = o.num_samples(), k = o.curve_points;
  check_memory(static_cast<double>(n) * static_cast<double>(o.num_inputs() + 7) * 8.0,
               "step_error dataset (" + std::to_string(n) + " samples x " +
                   std::to_string(o.num_inputs() + 7) + " values)");
  Dataset d;
  d.inputs.resize(static_cast<Eigen::Index>(o.num_inputs()), static_cast<Eigen::Index>(n));
  d.targets.resize(1, static_cast<Eigen::Index>(n));
  d.metadata.resize(6, static_cast<Eigen::Index>(n));
  Eigen::Index col = 0;
  for (std::size_t line = 0; line < o.tool_path.lines; ++line) {
    const ToolPathLine path = plan_line(o.surface, o.tool_path, line);
    for (std::size_t i = 0; i + 1 < path.u.size(); ++i, ++col) {
      const StepError e = exact_step_error(path.segment(i), o.exact);
      step_error_inputs(path, i, k, d.inputs.col(col));
      d.targets(0, col) = e.error * kUmPerMm;
      d.metadata.col(col) << static_cast<double>(line), static_cast<double>(i), path.u[i],
          path.u[i + 1], path.v, e.convex ? 1.0 : 0.0;
    }
  }
  const auto xyz = [&](const std::string& point) {
    for (const char* axis : {"_x", "_y", "_z"}) d.input_names.push_back(point + axis);
  };
  // (append, not operator+: GCC 12 -Wrestrict false positive on "p" + to_string)
  for (std::size_t j = 1; j <= k; ++j) xyz(std::string(1, 'p').append(std::to_string(j)));
  xyz("cc_i");
  xyz("cc_i+1");
  xyz("cl_i");
  xyz("cl_i+1");
  d.input_names.push_back("R");
  d.input_units.assign(d.input_names.size(), "mm");
  d.target_names = {"step_error"};
  d.target_units = {"µm"};
  d.metadata_names = {"line", "point", "u_i", "u_i+1", "v", "convex"};
  d.metadata_units.assign(d.metadata_names.size(), "1");
  d.generator = "step_error";
  return d;
}

}  // namespace

Dataset generate_step_error_dataset(const StepErrorDatasetOptions& o) {
  o.validate();
  return step_error_dataset_of_valid(o);
}

StepErrorGenerator::StepErrorGenerator(StepErrorDatasetOptions options)
    : options_(std::move(options)) {
  options_.validate();
}

Dataset StepErrorGenerator::generate(Rng&) const {
  return step_error_dataset_of_valid(options_);
}

namespace {

// `surface: {file: part.step, face: 3}`: a face of a CAD file (the file
// resolved like include:).
void read_cad_face(const ConfigReader& r, StepErrorDatasetOptions& o) {
  const ConfigReader s = r.section("surface");
  const std::filesystem::path file = named_config_file(s, "file");
  const auto face = s.require<std::int64_t>("face");
  s.check(face >= 1 && face <= 1'000'000, "face",
          "must be a face number >= 1 (faces count from 1)");
  try {
    auto cad = std::make_shared<CadSurface>(read_cad_surface(file, static_cast<int>(face)));
    o.surface = cad->surface;
    o.cad = std::move(cad);
  } catch (const ConfigError& e) {
    s.fail("file", e.what());
  }
}

// `surface:` as a file name (resolved like include:), an inline map or a CAD face.
void read_surface(const ConfigReader& r, StepErrorDatasetOptions& o) {
  if (!r.has("surface")) {
    r.fail("surface", "is required (a configs/surfaces/*.yaml path, a map or {file, face})");
  }
  o.cad.reset();
  const YAML::Node node = r.raw("surface");
  if (node.IsMap() && node["file"]) return read_cad_face(r, o);
  if (node.IsMap()) {
    o.surface = read_nurbs_surface(r.section("surface"));
    return;
  }
  const std::filesystem::path file = named_config_file(r, "surface");
  ConfigDocument doc;
  try {
    doc = ConfigDocument::load(file);
  } catch (const ConfigError& e) {
    r.fail("surface", e.what());
  }
  o.surface = read_nurbs_surface(doc.root());
  doc.check_all_consumed();
}

// The surface's identity in options_yaml(): the NURBS inline, or the CAD
// file's content hash with the face.
YAML::Node surface_node(const StepErrorDatasetOptions& o) {
  if (!o.cad) return YAML::Load(nurbs_surface_yaml(o.surface, ""));
  YAML::Node n(YAML::NodeType::Map);
  n["file_hash"] = o.cad->file_hash;
  n["face"] = o.cad->face;
  n["type"] = o.cad->surface_type;
  return n;
}

}  // namespace

const FieldList<StepErrorDatasetOptions>& step_error_fields() {
  using O = StepErrorDatasetOptions;
  using T = ToolPathOptions;
  static const auto tool_path =
      FieldList<T>()
          .field("lines", &T::lines, "N, tool-path lines along v (seed 000: 200)",
                 Rule::in(2, true, 1e6, true))
          .field("points_per_line", &T::points_per_line,
                 "M, CC points per line along u (seed 000: 100, so 99 segments)",
                 Rule::in(2, true, 1e6, true))
          .field("tool_radius", &T::tool_radius, "R, ball-end cutter radius [mm] (seed 000: 5)",
                 Rule::positive());
  static const auto fields =
      FieldList<O>()
          .custom(custom_info("surface",
                              "the machined NURBS surface (required): a configs/surfaces/*.yaml "
                              "path, an inline map, or {file: part.step|.stp|.iges|.igs, face: N} "
                              "(N from 1; `cnclab surface show` lists the faces)"),
                  read_surface, surface_node)
          .flatten(&O::tool_path, tool_path)
          .field("curve_points", &O::curve_points,
                 "K, points per local CC curve given as inputs (3K + 13 inputs; 73 at 20)",
                 Rule::in(1, true, 1e4, true));
  return fields;
}

std::string StepErrorGenerator::options_yaml() const {
  return step_error_fields().yaml(options_);
}

std::shared_ptr<const DatasetGenerator> read_step_error(const ConfigReader& r) {
  return read_declared_generator<StepErrorGenerator>(r, step_error_fields());
}

}  // namespace cnclab
