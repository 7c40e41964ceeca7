// Designs the three free-form test surfaces of seed 000 (bounding boxes
// 120 x 140 x 38, 135 x 175 x 68.28 and 150 x 150 x 54.02 mm; their models
// were not published) and prints their bounding boxes and step-error ranges
// with the paper's tool path (200 lines x 100 CC points, R = 5 mm).
//
// Construction (each surface): a bicubic NURBS on uniform clamped knots with
// 16 x 16 control points. x_ij = W g_i, y_ij = D g_j with g the Greville
// abscissae of the knot vector (so the boundary control points span
// [0, W] x [0, D] and x, y of the surface stay inside it); z_ij = f(x_i, y_j)
// for a smooth height function f with a wave along x (the feed direction u),
// which gives convex crests and concave troughs along every tool-path line;
// weights w_ij = 1 + a sin(..) sin(..) (a genuine rational surface). The z
// coordinates are then mapped affinely so the surface's z range is exactly
// the paper's height (NURBS are affinely invariant), and the wavelength of
// the wave along x is bisected until the largest step error equals the
// paper's maximum (13, 14, 9 µm).
//
// Usage: cnclab_design_surfaces [OUT_DIR]
//   Prints the report; with OUT_DIR writes OUT_DIR/surface{1,2,3}.yaml
//   (the committed configs/surfaces/*.yaml were made by
//   `build/bench/cnclab_design_surfaces configs/surfaces`).
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <string>

#include "cnclab/core/format.hpp"
#include "cnclab/data/step_error.hpp"
#include "cnclab/geometry/surface_config.hpp"

namespace {

using namespace cnclab;
constexpr double kPi = std::numbers::pi;
constexpr int kDegree = 3;
constexpr std::size_t kCount = 16;
constexpr int kBoxSamples = 801;

struct Design {
  std::string name;
  double width, depth, height;  // paper's bounding box [mm]
  double max_error_um;          // paper's largest step error [µm]
  std::string formula;          // f(x, y; lambda) in words, for the YAML header
  std::function<double(double x, double y, double lambda)> f;
  std::function<double(double s, double t)> weight;  // s, t in [0, 1]
};

std::vector<double> clamped_uniform_knots() {
  std::vector<double> k(kDegree + 1, 0.0);
  const std::size_t spans = kCount - kDegree;
  for (std::size_t i = 1; i < spans; ++i) k.push_back(static_cast<double>(i) / spans);
  k.insert(k.end(), kDegree + 1, 1.0);
  return k;
}

NurbsSurface build(const Design& d, double lambda) {
  NurbsSurface s;
  s.degree_u = s.degree_v = kDegree;
  s.knots_u = s.knots_v = clamped_uniform_knots();
  s.count_u = s.count_v = kCount;
  std::vector<double> greville(kCount);
  for (std::size_t i = 0; i < kCount; ++i) {
    double sum = 0.0;
    for (int k = 1; k <= kDegree; ++k) sum += s.knots_u[i + static_cast<std::size_t>(k)];
    greville[i] = sum / kDegree;
  }
  for (std::size_t i = 0; i < kCount; ++i) {
    for (std::size_t j = 0; j < kCount; ++j) {
      const double x = d.width * greville[i], y = d.depth * greville[j];
      s.points.emplace_back(x, y, d.f(x, y, lambda));
      s.weights.push_back(d.weight(greville[i], greville[j]));
    }
  }
  // z range of the surface -> [0, height] exactly (affine invariance).
  const BoundingBox box = sampled_bounding_box(s, kBoxSamples);
  const double scale = d.height / (box.max.z() - box.min.z());
  for (auto& p : s.points) p.z() = (p.z() - box.min.z()) * scale;
  return s;
}

struct Report {
  BoundingBox box;
  double min_concave_radius = 0;  // smallest concave radius of curvature along u [mm]
  double min_um = 0, max_um = 0;
  std::size_t convex = 0, samples = 0;
};

Report evaluate(const NurbsSurface& s, bool with_curvature = false) {
  StepErrorDatasetOptions o;
  o.surface = s;
  o.curve_points = 1;  // the inputs do not matter here
  const Dataset d = generate_step_error_dataset(o);
  Report r;
  r.box = sampled_bounding_box(s, kBoxSamples);
  // Radius of curvature of the CC curves |C'|^3 / |C' x C''|, concave where
  // C'' points to the tool side; the ball fits (no gouging along the feed)
  // while it stays above R.
  r.min_concave_radius = INFINITY;
  // The tool's side, once for the surface (they face +z throughout): the
  // side of S_u x S_v at the middle that points up.
  const SurfaceDerivatives middle = surface_derivatives(s, 0.5, 0.5);
  const double side = middle.du.cross(middle.dv).z() >= 0 ? 1.0 : -1.0;
  for (int a = 0; with_curvature && a <= 200; ++a) {
    for (int b = 0; b <= 1000; ++b) {
      const SurfaceDerivatives sd = surface_derivatives(s, b / 1000.0, a / 200.0);
      if (sd.duu.dot(side * sd.du.cross(sd.dv)) <= 0) continue;
      r.min_concave_radius =
          std::min(r.min_concave_radius, std::pow(sd.du.norm(), 3) / sd.du.cross(sd.duu).norm());
    }
  }
  r.min_um = d.targets.minCoeff();
  r.max_um = d.targets.maxCoeff();
  r.samples = d.num_samples();
  r.convex = static_cast<std::size_t>(d.metadata.row(d.metadata_row("convex")).sum());
  return r;
}

// Bisects lambda in [lo, hi] so that the largest step error is the paper's
// (the error falls as the wave gets longer).
double tune(const Design& d, double lo, double hi) {
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (evaluate(build(d, mid)).max_um > d.max_error_um) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

std::vector<Design> designs() {
  return {
      {"surface1", 120.0, 140.0, 38.0, 13.0,
       "f = sin(2 pi x / lambda + 0.3) + 0.35 cos(2 pi y / 110) + 0.15 sin(2 pi (x + y) / 90)",
       [](double x, double y, double l) {
         return std::sin(2 * kPi * x / l + 0.3) + 0.35 * std::cos(2 * kPi * y / 110.0) +
                0.15 * std::sin(2 * kPi * (x + y) / 90.0);
       },
       [](double s, double t) { return 1.0 + 0.2 * std::sin(kPi * s) * std::sin(kPi * t); }},
      {"surface2", 135.0, 175.0, 68.28, 14.0,
       "f = (1 + 0.4 y / 175) sin(2 pi x / lambda) + 1.2 (y / 175)^2 - 0.25 cos(2 pi (x - y) / "
       "160)",
       [](double x, double y, double l) {
         return (1.0 + 0.4 * y / 175.0) * std::sin(2 * kPi * x / l) +
                1.2 * (y / 175.0) * (y / 175.0) - 0.25 * std::cos(2 * kPi * (x - y) / 160.0);
       },
       [](double s, double t) { return 1.0 + 0.25 * std::sin(2 * kPi * s) * std::cos(kPi * t); }},
      {"surface3", 150.0, 150.0, 54.02, 9.0,
       "f = cos(2 pi x / lambda) cos(pi (y - 75) / 200) + 0.5 sin(2 pi y / 150 + 0.5 x / 150)",
       [](double x, double y, double l) {
         return std::cos(2 * kPi * x / l) * std::cos(kPi * (y - 75.0) / 200.0) +
                0.5 * std::sin(2 * kPi * y / 150.0 + 0.5 * x / 150.0);
       },
       [](double s, double t) { return 1.0 + 0.3 * s * (1.0 - s) * std::cos(2 * kPi * t); }},
  };
}

std::string fixed3(double x) {
  char text[64];
  std::snprintf(text, sizeof text, "%.3f", x);
  return text;
}

std::string sig3(double x) {
  char text[64];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}

void write_yaml(const std::string& dir, const Design& d, double lambda, const NurbsSurface& s,
                const Report& r) {
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + d.name + ".yaml";
  std::ofstream out(path);
  out << "# " << d.name << ": a free-form NURBS test surface with seed 000's bounding box "
      << shortest_double(d.width) << " x " << shortest_double(d.depth) << " x "
      << shortest_double(d.height) << " mm\n"
      << "# (the paper's models were not published). Made by bench/design_surfaces.cpp:\n"
      << "#   bicubic, 16 x 16 control points on uniform clamped knots; x, y at the\n"
      << "#   Greville abscissae times the box size; z from\n"
      << "#     " << d.formula << "\n"
      << "#   with lambda = " << fixed3(lambda)
      << " mm (bisected so the largest step error of the\n"
      << "#   paper's tool path, 200 lines x 100 CC points along u = x, R = 5 mm, is the paper's\n"
      << "#   " << shortest_double(d.max_error_um) << " µm), then mapped affinely onto z in [0, "
      << shortest_double(d.height) << "]; weights 1 +- a smooth bump.\n"
      << "# The wave along x gives convex crests and concave troughs on every tool-path line;\n"
      << "# the smallest concave radius of curvature along u is " << fixed3(r.min_concave_radius)
      << " mm (> R: no gouging along the feed).\n"
      << "# Bounding box (801 x 801 samples): " << fixed3(r.box.size().x()) << " x "
      << fixed3(r.box.size().y()) << " x " << fixed3(r.box.size().z()) << " mm; step errors ["
      << sig3(r.min_um) << ", " << sig3(r.max_um) << "] µm.\n"
      << "# Regenerate: build/bench/cnclab_design_surfaces configs/surfaces\n"
      << nurbs_surface_yaml(s, "");
  if (!out.flush()) {
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
    std::exit(1);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string out_dir = argc > 1 ? argv[1] : "";
  std::printf("%-9s %8s %26s %22s %10s %8s %s\n", "surface", "lambda", "bounding box [mm]",
              "step error [µm]", "paper", "convex", "min concave radius [mm]");
  for (const Design& d : designs()) {
    const double lambda = tune(d, 20.0, 2000.0);
    const NurbsSurface s = build(d, lambda);
    const Report r = evaluate(s, true);
    std::printf("%-9s %8.3f %8.3f x %7.3f x %6.3f [%9.3g, %8.4f] [0.01, %g] %7.1f%% %8.2f\n",
                d.name.c_str(), lambda, r.box.size().x(), r.box.size().y(), r.box.size().z(),
                r.min_um, r.max_um, d.max_error_um,
                100.0 * static_cast<double>(r.convex) / static_cast<double>(r.samples),
                r.min_concave_radius);
    if (!out_dir.empty()) write_yaml(out_dir, d, lambda, s, r);
  }
  return 0;
}
