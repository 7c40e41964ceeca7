#include "cnclab/data/step_error.hpp"

#include <cstdio>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/resources.hpp"
#include "cnclab/core/units.hpp"
#include "cnclab/data/declared_generator.hpp"
#include "cnclab/data/named_config_file.hpp"
#include "cnclab/geometry/surface_config.hpp"

namespace cnclab {

void StepErrorDatasetOptions::validate() const {
  surface.validate();
  tool_path.validate();
  exact.validate();
  if (curve_points < 1 || curve_points > 10'000) {
    throw OptionError("curve_points", std::to_string(curve_points), "must be in [1, 10000]");
  }
}

FaceContext StepErrorDatasetOptions::face() const {
  if (cad) return cad->context;
  FaceContext f;
  f.label = surface_name;
  return f;
}

void step_error_inputs(const ToolPathLine& line, std::size_t i, std::size_t k,
                       Eigen::Ref<Eigen::VectorXd> x) {
  const double dt = (line.t[i + 1] - line.t[i]) / static_cast<double>(k + 1);
  for (std::size_t j = 0; j < k; ++j) {
    x.segment<3>(static_cast<Eigen::Index>(3 * j)) =
        curve_point(line.curve, line.t[i] + dt * static_cast<double>(j + 1));
  }
  const auto base = static_cast<Eigen::Index>(3 * k);
  x.segment<3>(base) = line.cc[i];
  x.segment<3>(base + 3) = line.cc[i + 1];
  x.segment<3>(base + 6) = line.cl[i];
  x.segment<3>(base + 9) = line.cl[i + 1];
  x(base + 12) = line.tool_radius;
}

namespace {

// The step error of pair i of `line`: ConfigError naming the face, the line
// and the pair where it is undefined (coinciding CL points: R equal to a
// concave radius) or not below R (the last line of defence: e = |R - L|
// reaches R only where the CC curve touches the CL line, L = 0, or lies
// more than 2R from it; either way the tool's envelope no longer models the
// cut, whatever let the segment through).
StepError checked_step_error(const StepErrorDatasetOptions& o, const ToolPathLine& line,
                             std::size_t i) {
  const std::string where = (o.cad ? o.cad->label() : o.surface_name) + ": " + line.label() +
                            ", CC points " + std::to_string(i) + " and " + std::to_string(i + 1);
  StepError e;
  try {
    e = exact_step_error(line.segment(i), o.exact);
  } catch (const ConfigError&) {
    throw;
  } catch (const Error& error) {
    throw ConfigError(where + ": " + error.what());
  }
  if (!(e.error < line.tool_radius)) {
    char error[32];
    std::snprintf(error, sizeof error, "%.6g", e.error);
    throw ConfigError(where + ": the step error " + std::string(error) +
                      " mm is not below the tool radius R = " + shortest_double(line.tool_radius) +
                      " mm: the CL line leaves the tool's reach (the CC points are too far apart "
                      "for the surface's curvature there); use more points_per_line");
  }
  return e;
}

// The dataset of validated options on their planned path.
Dataset step_error_dataset_of_valid(const StepErrorDatasetOptions& o, const ToolPath& path) {
  const std::size_t n = path.samples.size(), k = o.curve_points;
  const std::vector<std::string> metadata = {"line",  "segment", "point",  "u_i",  "v_i",
                                             "u_i+1", "v_i+1",   "convex", "gouge"};
  check_memory(
      static_cast<double>(n) * static_cast<double>(o.num_inputs() + metadata.size() + 1) * 8.0,
      "step_error dataset (" + std::to_string(n) + " samples x " +
          std::to_string(o.num_inputs() + metadata.size() + 1) + " values)");
  Dataset d;
  d.inputs.resize(static_cast<Eigen::Index>(o.num_inputs()), static_cast<Eigen::Index>(n));
  d.targets.resize(1, static_cast<Eigen::Index>(n));
  d.metadata.resize(static_cast<Eigen::Index>(metadata.size()), static_cast<Eigen::Index>(n));
  for (std::size_t s = 0; s < n; ++s) {
    const PathSample& sample = path.samples[s];
    const ToolPathLine& line = path.lines[sample.line];
    const std::size_t i = sample.point;
    const StepError e = checked_step_error(o, line, i);
    const auto col = static_cast<Eigen::Index>(s);
    step_error_inputs(line, i, k, d.inputs.col(col));
    d.targets(0, col) = e.error * kUmPerMm;
    const Eigen::Vector2d a = line.uv(line.t[i]), b = line.uv(line.t[i + 1]);
    d.metadata.col(col) << static_cast<double>(sample.line), static_cast<double>(sample.run),
        static_cast<double>(i), a.x(), a.y(), b.x(), b.y(), e.convex ? 1.0 : 0.0,
        static_cast<double>(line.gouge[i]);
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
  d.metadata_names = metadata;
  d.metadata_units.assign(d.metadata_names.size(), "1");
  d.generator = "step_error";
  return d;
}

}  // namespace

Dataset generate_step_error_dataset(const StepErrorDatasetOptions& o) {
  o.validate();
  return step_error_dataset_of_valid(o, plan_tool_path(o.surface, o.tool_path, o.face()));
}

StepErrorGenerator::StepErrorGenerator(StepErrorDatasetOptions options)
    : options_(std::move(options)) {
  options_.validate();
  path_ = std::make_shared<const ToolPath>(
      plan_tool_path(options_.surface, options_.tool_path, options_.face()));
}

Dataset StepErrorGenerator::generate(Rng&) const {
  return step_error_dataset_of_valid(options_, *path_);
}

namespace {

// `surface: {file: part.step, face: 3, read_timeout: 600}`: a face of a CAD
// file (the file resolved like include:).
void read_cad_face(const ConfigReader& r, StepErrorDatasetOptions& o) {
  const ConfigReader s = r.section("surface");
  const std::filesystem::path file = named_config_file(s, "file");
  const auto face = s.require<std::int64_t>("face");
  s.check(face >= 1 && face <= 1'000'000, "face",
          "must be a face number >= 1 (faces count from 1)");
  CadReadOptions read;
  read.read_timeout = s.get<double>("read_timeout", read.read_timeout);
  s.validate([&] { read.validate(); });
  try {
    auto cad = std::make_shared<CadSurface>(read_cad_surface(file, static_cast<int>(face), read));
    o.surface = cad->surface;
    o.surface_name = cad->label();
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
    o.surface_name = "the inline surface";
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
  o.surface_name = "surface " + file.string();
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
                 Rule::positive())
          .choice("feed", &T::feed, {{"u", FeedDirection::u}, {"v", FeedDirection::v}},
                  "the parameter the CC points run along; lines at constant other (seed 000: u)")
          .field("tool_axis", &T::tool_axis,
                 "[x, y, z]: the tool's axis, machining from its + side (default +z)")
          .field("max_normal_angle", &T::max_normal_angle,
                 "largest angle [deg] between the normal on the tool side and the tool axis; "
                 "steeper is unreachable",
                 Rule::in(0, false, 90, true))
          .choice("unreachable", &T::unreachable,
                  {{"refuse", UnreachablePolicy::refuse}, {"clip", UnreachablePolicy::clip}},
                  "unreachable or degenerate CC points (poles): refuse (exit 2 naming the face, "
                  "line and point) or clip (cut from the path like trims)")
          .choice("gouge", &T::gouge,
                  {{"refuse", GougePolicy::refuse}, {"allow", GougePolicy::allow}},
                  "tool radius above a concave radius of curvature: refuse, or allow (flagged "
                  "in the `gouge` metadata column)")
          .choice(
              "tool_side", &T::tool_side,
              {{"auto", ToolSide::automatic}, {"front", ToolSide::front}, {"back", ToolSide::back}},
              "the face's side the tool works from: auto (a solid's face from outside, "
              "else the side facing the tool axis), front (its normal), back");
  static const auto fields =
      FieldList<O>()
          .custom(custom_info("surface",
                              "the machined NURBS surface (required): a configs/surfaces/*.yaml "
                              "path, an inline map, or {file: part.step|.stp|.iges|.igs, face: N} "
                              "(N from 1; `cnclab surface show` lists the faces; optional "
                              "read_timeout: seconds, default 60 + 10 per MB)"),
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
