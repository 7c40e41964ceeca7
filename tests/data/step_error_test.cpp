#include "cnclab/data/step_error.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/data/dataset_file.hpp"
#include "cnclab/data/generator.hpp"
#include "cnclab/geometry/surface_config.hpp"
#include "common/expect_error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

const std::string kSurface1 = CNCLAB_SOURCE_DIR "/configs/surfaces/surface1.yaml";

// A small tool path on surface 1: 4 lines x 6 CC points, K = 3.
std::string small_config(const std::string& surface, const std::string& extra = "") {
  return "dataset:\n  generator: step_error\n  options:\n    surface: " + surface +
         "\n    lines: 4\n    points_per_line: 6\n    tool_radius: 4.5\n    curve_points: 3\n" +
         extra;
}

struct Loaded {
  ConfigDocument doc;
  std::shared_ptr<const DatasetGenerator> generator;
};

Loaded load(const fs::path& file) {
  Loaded l{ConfigDocument::load(file), nullptr};
  l.generator = read_generator(l.doc.root().section("dataset"));
  l.doc.check_all_consumed();
  return l;
}

fs::path write(const TempDir& dir, const std::string& name, const std::string& text) {
  fs::create_directories((dir / name).parent_path());
  std::ofstream(dir / name) << text;
  return dir / name;
}

NurbsSurface surface1() {
  const ConfigDocument doc = ConfigDocument::load(kSurface1);
  return read_nurbs_surface(doc.root());
}

// Every value checked against the surface evaluated independently of the
// tool-path code: p_j and CC points at their parameters, CL = CC + R n with n
// the surface normal, and the target against a 20,001-point scan of L.
TEST(StepErrorGenerator, SamplesAreTheSurfaceGeometryThroughTheRegistry) {
  TempDir dir;
  const Loaded l = load(write(dir, "d.yaml", small_config(kSurface1)));
  EXPECT_EQ(l.generator->name(), "step_error");
  const DatasetShape shape = l.generator->shape();
  EXPECT_EQ(shape.samples, 4u * 5u);
  EXPECT_EQ(shape.inputs, 3u * 3u + 13u);
  Rng unused(0);
  const Dataset d = l.generator->generate(unused);
  d.validate();
  ASSERT_EQ(d.num_samples(), shape.samples);
  ASSERT_EQ(static_cast<std::size_t>(d.inputs.rows()), shape.inputs);
  EXPECT_EQ(d.input_names.front(), "p1_x");
  EXPECT_EQ(d.input_names[9], "cc_i_x");
  EXPECT_EQ(d.input_names.back(), "R");
  EXPECT_EQ(d.input_units, std::vector<std::string>(shape.inputs, "mm"));
  EXPECT_EQ(d.target_units, std::vector<std::string>{"µm"});
  EXPECT_EQ(d.metadata_names, (std::vector<std::string>{"line", "segment", "point", "u_i", "v_i",
                                                        "u_i+1", "v_i+1", "convex", "gouge"}));

  const NurbsSurface s = surface1();
  const double r = 4.5;
  std::size_t convex = 0;
  for (Eigen::Index j = 0; j < d.inputs.cols(); ++j) {
    const double line = d.metadata(0, j), point = d.metadata(2, j);
    const double u0 = d.metadata(3, j), u1 = d.metadata(5, j), v = d.metadata(4, j);
    EXPECT_EQ(d.metadata(1, j), 0.0);  // one segment per line: nothing is cut
    EXPECT_EQ(d.metadata(6, j), v);
    EXPECT_EQ(d.metadata(8, j), 0.0);  // no gouge
    EXPECT_DOUBLE_EQ(v, line / 3.0);
    EXPECT_NEAR(u0, point / 5.0, 1e-15);
    EXPECT_NEAR(u1, (point + 1) / 5.0, 1e-15);
    const auto x = d.inputs.col(j);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = surface_point(s, u0 + (u1 - u0) * (k + 1) / 4.0, v);
      EXPECT_NEAR((x.segment<3>(3 * k) - p).norm(), 0.0, 1e-11);
    }
    const Eigen::Vector3d cc0 = x.segment<3>(9), cc1 = x.segment<3>(12);
    const Eigen::Vector3d cl0 = x.segment<3>(15), cl1 = x.segment<3>(18);
    EXPECT_NEAR((cc0 - surface_point(s, u0, v)).norm(), 0.0, 1e-11);
    EXPECT_NEAR((cc1 - surface_point(s, u1, v)).norm(), 0.0, 1e-11);
    const SurfaceDerivatives sd = surface_derivatives(s, u0, v);
    Eigen::Vector3d n = sd.du.cross(sd.dv).normalized();
    if (n.z() < 0) n = -n;
    EXPECT_NEAR((cl0 - (cc0 + r * n)).norm(), 0.0, 1e-11);
    EXPECT_NEAR((cl1 - cc1).norm(), r, 1e-11);
    EXPECT_EQ(x(21), r);
    // Scan of L (seed 000 Eq. 1) over the segment.
    const Eigen::Vector3d axis = (cl1 - cl0).normalized();
    const bool is_convex = d.metadata(7, j) == 1.0;
    convex += is_convex;
    double extreme = is_convex ? INFINITY : -INFINITY;
    for (int k = 0; k <= 20'000; ++k) {
      const Eigen::Vector3d p = surface_point(s, u0 + (u1 - u0) * k / 20'000.0, v);
      const double l = (p - cl0).cross(axis).norm();
      extreme = is_convex ? std::min(extreme, l) : std::max(extreme, l);
    }
    // The scan's own error grows with the (deliberately coarse, ~24 mm) step.
    EXPECT_NEAR(d.targets(0, j), 1000.0 * std::abs(r - extreme), 1e-8 * d.targets(0, j) + 1e-6)
        << "sample " << j;
  }
  EXPECT_GT(convex, 0u);
  EXPECT_LT(convex, d.num_samples());
}

// The resolved options (surface inline) read back to the same generator.
TEST(StepErrorGenerator, OptionsYamlRoundTrips) {
  TempDir dir;
  const Loaded a = load(write(dir, "a.yaml", small_config(kSurface1)));
  std::string inline_text = "dataset:\n  generator: step_error\n  options:\n";
  const std::string options = a.generator->options_yaml();
  std::size_t start = 0;
  while (start < options.size()) {
    const std::size_t end = options.find('\n', start);
    inline_text += "    " + options.substr(start, end - start) + "\n";
    start = end + 1;
  }
  const Loaded b = load(write(dir, "b.yaml", inline_text));
  EXPECT_EQ(b.generator->options_yaml(), options);
  Rng unused(0);
  EXPECT_EQ(a.generator->generate(unused).content_hash(),
            b.generator->generate(unused).content_hash());
}

// "configs/..." resolves against the nearest ancestor holding configs/.
TEST(StepErrorGenerator, SurfacePathResolvesLikeInclude) {
  TempDir dir;
  std::ifstream in(kSurface1);
  std::stringstream text;
  text << in.rdbuf();
  write(dir, "configs/surfaces/mine.yaml", text.str());
  const fs::path config =
      write(dir, "configs/datasets/d.yaml", small_config("configs/surfaces/mine.yaml"));
  EXPECT_EQ(load(config).generator->shape().samples, 20u);
}

// Seed 000's three surfaces with its tool path (200 x 100, R = 5 mm): the
// paper's bounding boxes within 0.5 %, largest step error within 25 % of the
// paper's, smallest below 0.05 µm, convex and concave segments on each.
TEST(StepErrorGenerator, TheThreeSurfacesMatchThePapersBoxesAndRanges) {
  struct Paper {
    const char* file;
    double box[3], max_um;
  };
  for (const Paper& p :
       {Paper{"/surface1.yaml", {120, 140, 38}, 13}, Paper{"/surface2.yaml", {135, 175, 68.28}, 14},
        Paper{"/surface3.yaml", {150, 150, 54.02}, 9}}) {
    const ConfigDocument doc =
        ConfigDocument::load(std::string(CNCLAB_SOURCE_DIR "/configs/surfaces") + p.file);
    StepErrorDatasetOptions o;
    o.surface = read_nurbs_surface(doc.root());
    o.curve_points = 1;  // inputs do not matter here
    const Dataset d = generate_step_error_dataset(o);
    // Reachable from +z, no pole, no gouge at R = 5 mm: the whole grid.
    EXPECT_EQ(d.num_samples(), 19'800u);
    const Eigen::Vector3d size = sampled_bounding_box(o.surface, 401).size();
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(size(a), p.box[a], 0.005 * p.box[a]) << p.file;
    EXPECT_NEAR(d.targets.maxCoeff(), p.max_um, 0.25 * p.max_um) << p.file;
    EXPECT_LT(d.targets.minCoeff(), 0.05) << p.file;
    const double convex_share = d.metadata.row(d.metadata_row("convex")).mean();
    EXPECT_GT(convex_share, 0.1) << p.file;
    EXPECT_LT(convex_share, 0.9) << p.file;
  }
}

std::string config_error(const std::string& text) {
  TempDir dir;
  return testing::error_message<ConfigError>([&] { load(write(dir, "bad.yaml", text)); });
}

TEST(StepErrorGenerator, BadOptionsAreLocatedConfigErrors) {
  std::string radius = small_config(kSurface1);
  radius.replace(radius.find("tool_radius: 4.5"), 16, "tool_radius: 0");
  const std::string m = config_error(radius);
  EXPECT_NE(m.find("bad.yaml:7:18:"), std::string::npos) << m;
  EXPECT_NE(m.find("dataset.options.tool_radius = 0: must be a finite ball radius > 0 mm"),
            std::string::npos)
      << m;
  std::string points = small_config(kSurface1);
  points.replace(points.find("points_per_line: 6"), 18, "points_per_line: 1");
  EXPECT_NE(config_error(points).find("points_per_line = 1: must be in [2, 1000000]"),
            std::string::npos);
  std::string k = small_config(kSurface1);
  k.replace(k.find("curve_points: 3"), 15, "curve_points: 0");
  EXPECT_NE(config_error(k).find("curve_points = 0"), std::string::npos);
  EXPECT_NE(config_error(small_config("/nonexistent/surface.yaml"))
                .find("not found; looked in: /nonexistent/surface.yaml"),
            std::string::npos);
  EXPECT_NE(config_error(small_config(kSurface1, "    speed: 3\n")).find("dataset.options.speed"),
            std::string::npos);
  std::string no_surface = small_config(kSurface1);
  no_surface.replace(no_surface.find("surface: "), 9 + kSurface1.size(), "lines_: 2");
  EXPECT_NE(config_error(no_surface).find("dataset.options.surface: is required"),
            std::string::npos)
      << config_error(no_surface);
  // An inline surface with a bad knot vector names the key in this file.
  const std::string bad_knots =
      "dataset:\n  generator: step_error\n  options:\n    surface:\n      degree_u: 1\n"
      "      degree_v: 1\n      knots_u: [0, 1, 0, 1]\n      knots_v: [0, 0, 1, 1]\n"
      "      control_points: [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]]\n";
  const std::string km = config_error(bad_knots);
  EXPECT_NE(km.find("bad.yaml:"), std::string::npos) << km;
  EXPECT_NE(km.find("non-decreasing"), std::string::npos) << km;
}

// The last line of defence: a step error not below R (here a 120 deg step
// inside a 1 mm cylinder with R = 0.1 mm: the arc's middle lies
// L = rho - (rho - R) cos 60 deg = 0.55 mm from the CL line, so
// e = L - R = 0.45 mm) is refused naming the surface, the line and the CC
// points; steps of theta below 20 deg give e = (rho - R)(1 - cos(theta/2)).
TEST(StepErrorGenerator, StepErrorNotBelowTheToolRadiusIsRefused) {
  const std::string cylinder =
      "{degree_u: 2, degree_v: 1, knots_u: [0, 0, 0, 1, 1, 1], knots_v: [0, 0, 1, 1], "
      "control_points: [[[-0.866025403784439, 0, -0.5], [-0.866025403784439, 10, -0.5]], "
      "[[0, 0, -2], [0, 10, -2]], [[0.866025403784439, 0, -0.5], [0.866025403784439, 10, -0.5]]], "
      "weights: [[1, 1], [0.5, 0.5], [1, 1]]}";
  std::string text = small_config(cylinder);
  text.replace(text.find("points_per_line: 6"), 18, "points_per_line: 2");
  text.replace(text.find("tool_radius: 4.5"), 16, "tool_radius: 0.1");
  TempDir dir;
  const Loaded coarse = load(write(dir, "coarse.yaml", text));
  Rng unused(0);
  const std::string m =
      testing::error_message<ConfigError>([&] { coarse.generator->generate(unused); });
  EXPECT_NE(m.find("the inline surface: line 0 (v = 0), CC points 0 and 1: the step error 0.45 mm "
                   "is not below the tool radius R = 0.1 mm"),
            std::string::npos)
      << m;
  text.replace(text.find("points_per_line: 2"), 18, "points_per_line: 9");
  const Loaded fine = load(write(dir, "fine.yaml", text));
  const Dataset d = fine.generator->generate(unused);
  ASSERT_EQ(d.num_samples(), 4u * 8u);
  for (Eigen::Index j = 0; j < d.targets.cols(); ++j) {
    const auto x = d.inputs.col(j);  // CC_i at 9..11, CC_i+1 at 12..14 (K = 3)
    const double theta = std::abs(std::atan2(x(14), x(12)) - std::atan2(x(11), x(9)));
    EXPECT_NEAR(d.targets(0, j), 900 * (1 - std::cos(theta / 2)), 1e-6);
  }
}

// Options given as keys of dataset.options, read back in options_yaml().
TEST(StepErrorGenerator, MachiningOptionsAreDeclaredKeys) {
  TempDir dir;
  const Loaded l = load(write(dir, "d.yaml",
                              small_config(kSurface1,
                                           "    feed: v\n    tool_axis: [0, 0, 2]\n"
                                           "    max_normal_angle: 89\n"
                                           "    unreachable: clip\n    gouge: allow\n"
                                           "    tool_side: front\n")));
  const std::string yaml = l.generator->options_yaml();
  for (const char* key : {"feed: v", "tool_axis: [0, 0, 2]", "max_normal_angle: 89",
                          "unreachable: clip", "gouge: allow", "tool_side: front"}) {
    EXPECT_NE(yaml.find(key), std::string::npos) << key << "\n" << yaml;
  }
  // Feed along v: lines at constant u (4 of them), 6 CC points each along v.
  Rng unused(0);
  const Dataset d = l.generator->generate(unused);
  EXPECT_EQ(d.num_samples(), 4u * 5u);
  for (Eigen::Index j = 0; j < d.inputs.cols(); ++j) {
    EXPECT_EQ(d.metadata(3, j), d.metadata(5, j));  // u fixed along the line
    EXPECT_NEAR(d.metadata(3, j), d.metadata(0, j) / 3.0, 1e-15);
    EXPECT_LT(d.metadata(4, j), d.metadata(6, j));
  }
  EXPECT_NE(config_error(small_config(kSurface1, "    feed: w\n")).find("feed = w"),
            std::string::npos);
  EXPECT_NE(config_error(small_config(kSurface1, "    unreachable: skip\n")).find("refuse, clip"),
            std::string::npos)
      << config_error(small_config(kSurface1, "    unreachable: skip\n"));
}

}  // namespace
}  // namespace cnclab
