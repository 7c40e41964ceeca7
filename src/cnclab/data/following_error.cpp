#include "cnclab/data/following_error.hpp"

#include <cmath>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/resources.hpp"
#include "cnclab/core/units.hpp"
#include "cnclab/data/declared_generator.hpp"
#include "cnclab/data/named_config_file.hpp"
#include "cnclab/motion/contour_error.hpp"
#include "cnclab/motion/interpolator.hpp"
#include "cnclab/motion/machine_fields.hpp"
#include "cnclab/motion/smoothing_spline.hpp"

namespace cnclab {
namespace {

constexpr const char* kAxis[2] = {"x", "y"};

const std::vector<std::string> kMetadata = {"time",
                                            "u",
                                            "ref_x",
                                            "ref_y",
                                            "actual_x",
                                            "actual_y",
                                            "v_ref_x",
                                            "v_ref_y",
                                            "e_ref_x",
                                            "e_ref_y",
                                            "d1_x",
                                            "d1_y",
                                            "d2_x",
                                            "d2_y",
                                            "contour_exact",
                                            "contour_taylor",
                                            "contour_tangent",
                                            "contour_osculating",
                                            "validation"};
const std::vector<std::string> kMetadataUnits = {"s",    "1",  "mm", "mm", "mm", "mm", "mm/s",
                                                 "mm/s", "µm", "µm", "mm", "mm", "mm", "mm",
                                                 "µm",   "µm", "µm", "µm", "1"};

}  // namespace

void FollowingErrorOptions::validate() const {
  auto prefixed = [](const std::string& prefix, auto&& f) {
    try {
      f();
    } catch (const OptionError& e) {
      throw OptionError(prefix + e.field(), e.value(), e.rule());
    }
  };
  prefixed("path.", [&] { path.validate(); });
  prefixed("", [&] { planner.validate(); });
  prefixed("machine.", [&] { machine.validate(); });
  if (runs < 1 || runs > 1000) {
    throw OptionError("runs", std::to_string(runs), "must be in [1, 1000]");
  }
  if (!(smoothing >= 0.0 && smoothing <= 1.0)) {
    throw OptionError("smoothing", shortest_double(smoothing), "must be in [0, 1] (csaps p)");
  }
  if (samples != 0 && samples < 8) {
    throw OptionError("samples", std::to_string(samples), "must be 0 (whole run) or >= 8");
  }
}

Eigen::VectorXd normalise_minmax(const Eigen::VectorXd& x, const std::string& what,
                                 ColumnRange* range) {
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i])) {
      throw Error(what + ": sample " + std::to_string(i) + " is " + shortest_double(x[i]) +
                  " (not finite); cannot normalise");
    }
  }
  const double lo = x.size() ? x.minCoeff() : 0.0, hi = x.size() ? x.maxCoeff() : 0.0;
  if (!(hi > lo)) {
    throw Error(what + ": constant column (min = max = " + shortest_double(lo) +
                "); cannot map to [-1, 1]");
  }
  if (range) *range = {lo, hi};
  // MATLAB mapminmax: y = (ymax - ymin)(x - xmin)/(xmax - xmin) + ymin.
  Eigen::VectorXd y = ((x.array() - lo) / (hi - lo) * 2.0 - 1.0).matrix();
  return y;
}

Dataset generate_following_error_dataset(const FollowingErrorOptions& o, Rng& rng,
                                         const ProgressCallback& progress) {
  o.validate();
  // 1. Path, feedrate, 1 ms references.
  const NurbsPlanarPath path(random_planar_nurbs(o.path, rng));
  const std::uint64_t run_seed = rng.next_u64();
  const FeedrateProfile profile = plan_feedrate(path, o.planner, progress);
  const ReferenceTrajectory ref = interpolate(path, profile, o.machine.timing.controller_period);
  const Eigen::Index total = ref.samples();
  if (o.samples != 0 && static_cast<std::size_t>(total) < o.samples) {
    std::ostringstream m;
    m << "following_error: the planned run has " << total << " samples (" << profile.total_time()
      << " s) < samples = " << o.samples << "; raise path.control_points (now "
      << o.path.control_points << ") or lower samples";
    throw Error(m.str());
  }
  const Eigen::Index n = o.samples == 0 ? total : static_cast<Eigen::Index>(o.samples);
  check_memory(static_cast<double>(n) * (kMetadata.size() + 4 + 2 * o.runs) * 8.0,
               "following_error dataset");

  // 2. `runs` repetitions, each with its own noise streams; mean of the runs.
  Eigen::MatrixX2d mean_error = Eigen::MatrixX2d::Zero(total, 2);
  for (std::size_t k = 0; k < o.runs; ++k) {
    const MachineResponse r =
        simulate_machine(o.machine, ref, derive_seed(run_seed, "run/" + std::to_string(k)));
    mean_error += r.following_error;
    if (progress) progress("simulate runs", k + 1, o.runs);
  }
  mean_error /= static_cast<double>(o.runs);

  // 3. csaps smoothing on the sample index (see smoothing_spline.hpp), of the
  // kept samples.
  Eigen::VectorXd index(n);
  for (Eigen::Index i = 0; i < n; ++i) index[i] = static_cast<double>(i);
  Eigen::MatrixX2d e(n, 2);  // [mm]
  for (int a = 0; a < 2; ++a) {
    const Eigen::VectorXd raw = mean_error.col(a).head(n);
    e.col(a) = SmoothingSpline::fit(index, raw, o.smoothing).values();
  }

  // 4. Columns, contour errors and the normalisation.
  Dataset d;
  d.inputs.resize(2, n);
  d.targets.resize(2, n);
  d.metadata.resize(static_cast<Eigen::Index>(kMetadata.size()), n);
  for (int a = 0; a < 2; ++a) {
    const Eigen::VectorXd v = ref.velocity.col(a).head(n);
    const Eigen::VectorXd err_um = e.col(a) * kUmPerMm;
    d.inputs.row(a) = normalise_minmax(v, std::string("v_ref_") + kAxis[a]).transpose();
    d.targets.row(a) = normalise_minmax(err_um, std::string("e_ref_") + kAxis[a]).transpose();
  }
  for (Eigen::Index k = 0; k < n; ++k) {
    const PathPoint p = path.evaluate(ref.u[static_cast<std::size_t>(k)]);
    const Vec2 r = ref.position.row(k).transpose();
    const Vec2 actual = r - e.row(k).transpose();
    const double exact = project_to_path(path, actual, ref.u[static_cast<std::size_t>(k)]).distance;
    d.metadata.col(k) << ref.time[static_cast<std::size_t>(k)], ref.u[static_cast<std::size_t>(k)],
        r.x(), r.y(), actual.x(), actual.y(), ref.velocity(k, 0), ref.velocity(k, 1),
        e(k, 0) * kUmPerMm, e(k, 1) * kUmPerMm, p.d1.x(), p.d1.y(), p.d2.x(), p.d2.y(),
        exact * kUmPerMm, std::abs(taylor_contour_error(p, actual)) * kUmPerMm,
        tangent_line_contour_error(p, actual) * kUmPerMm,
        osculating_circle_contour_error(p, actual) * kUmPerMm, k >= n / 2 ? 1.0 : 0.0;
    if (progress && ((k + 1) % 1000 == 0 || k + 1 == n)) {
      progress("contour errors", static_cast<std::size_t>(k + 1), static_cast<std::size_t>(n));
    }
  }
  d.input_names = {"v_x", "v_y"};
  d.input_units = {"1", "1"};
  d.target_names = {"e_x", "e_y"};
  d.target_units = {"1", "1"};
  d.metadata_names = kMetadata;
  d.metadata_units = kMetadataUnits;
  d.generator = "following_error";
  d.validate();
  return d;
}

FollowingErrorRanges following_error_ranges(const Dataset& d) {
  auto range = [&](const std::string& name) {
    const Eigen::Index row = d.metadata_row(name);
    if (row < 0) throw Error("following_error dataset: no metadata column " + name);
    return ColumnRange{d.metadata.row(row).minCoeff(), d.metadata.row(row).maxCoeff()};
  };
  FollowingErrorRanges r;
  for (int a = 0; a < 2; ++a) {
    r.velocity[a] = range(std::string("v_ref_") + kAxis[a]);
    r.following_error[a] = range(std::string("e_ref_") + kAxis[a]);
  }
  return r;
}

std::size_t first_validation_sample(const Dataset& d) {
  return d.num_samples() / 2;
}

FollowingErrorGenerator::FollowingErrorGenerator(FollowingErrorOptions options)
    : options_(std::move(options)) {
  options_.validate();
}

namespace {

MachineOptions read_machine_option(const ConfigReader& r) {
  // Absent: the struct defaults, which are configs/machines/biaxial_router.yaml's.
  if (!r.has("machine")) return MachineOptions{};
  const YAML::Node node = r.raw("machine");
  if (node.IsMap()) return read_machine(r.section("machine"));
  const std::filesystem::path file = named_config_file(r, "machine");
  try {
    return load_machine(file);
  } catch (const ConfigError& e) {
    r.fail("machine", e.what());
  }
}

}  // namespace

const FieldList<FollowingErrorOptions>& following_error_fields() {
  using O = FollowingErrorOptions;
  using P = RandomNurbsPathOptions;
  using L = AxisLimits;
  using F = FeedratePlannerOptions;
  static const auto path =
      FieldList<P>()
          .field("degree", &P::degree,
                 "curve degree p (4: C''' continuous, so the jerk limit holds between nodes)",
                 Rule::in(1, true, 15, true))
          .field("control_points", &P::control_points, "control points, >= degree + 1",
                 Rule::at_least(2))
          .field("x_min", &P::x_min, "work area [mm]", Rule::finite_number())
          .field("x_max", &P::x_max, "work area [mm], > x_min", Rule::finite_number())
          .field("y_min", &P::y_min, "work area [mm]", Rule::finite_number())
          .field("y_max", &P::y_max, "work area [mm], > y_min", Rule::finite_number())
          .field("step_min", &P::step_min, "random-walk step between control points [mm]",
                 Rule::positive())
          .field("step_max", &P::step_max,
                 "[mm], >= step_min and <= half the smaller side of the area", Rule::positive())
          .field("max_turn", &P::max_turn, "largest heading change per step [deg]",
                 Rule::in(0, true, 180, true))
          .field("weight_min", &P::weight_min, "NURBS weights uniform in [min, max]",
                 Rule::positive())
          .field("weight_max", &P::weight_max, ">= weight_min; both 1: a B-spline",
                 Rule::positive())
          .field("min_curvature_radius", &P::min_curvature_radius,
                 "smallest radius of curvature on the curve [mm] (seed 002 Eq. 5); 0: no check",
                 Rule::non_negative());
  static const auto limits =
      FieldList<L>()
          .field("velocity", &L::velocity, "max |axis velocity| [mm/s] (seed 002: 300)",
                 Rule::positive())
          .field("acceleration", &L::acceleration,
                 "max |axis acceleration| [mm/s²] (seed 002: 2000)", Rule::positive())
          .field("jerk", &L::jerk, "max |axis jerk| [mm/s³] (seed 002: 50000)", Rule::positive());
  static const auto planner = FieldList<F>().field(
      "grid_spacing", &F::grid_spacing, "planning grid along the path [mm]", Rule::positive());
  static const auto fields = [] {
    FieldInfo limits_info =
        custom_info("limits", "per-axis limits, the same for x and y", FieldKind::section);
    limits_info.children = limits.info();
    // A file name or a map: FieldKind::any with the map's declarations.
    FieldInfo machine_info = custom_info(
        "machine",
        "the simulated machine: a configs/machines/*.yaml path or a map (motion/machine.hpp); "
        "absent: biaxial_router's values");
    machine_info.children = machine_fields().info();
    return FieldList<O>()
        .section("path", &O::path, path, "the random NURBS tool path")
        .custom(
            limits_info,
            [](const ConfigReader& r, O& o) {
              L l = o.planner.limits.axes[0];
              limits.read(r.section("limits"), l);
              r.section("limits").validate([&] { l.validate(); });
              o.planner.limits.axes = {l, l};
            },
            [](const O& o) { return limits.to_node(o.planner.limits.axes[0]); })
        .flatten(&O::planner, planner)
        .custom(
            machine_info, [](const ConfigReader& r, O& o) { o.machine = read_machine_option(r); },
            [](const O& o) { return machine_fields().to_node(o.machine); })
        .field("runs", &O::runs, "simulated runs averaged (seed 002: 10)",
               Rule::in(1, true, 1000, true))
        .field("smoothing", &O::smoothing, "csaps p on the sample index (seed 002: 0.05)",
               Rule::in(0, true, 1, true))
        .field("samples", &O::samples,
               "samples kept from the start (seed 002: over 170000); 0: the whole run");
  }();
  return fields;
}

std::string FollowingErrorGenerator::options_yaml() const {
  return following_error_fields().yaml(options_);
}

std::shared_ptr<const DatasetGenerator> read_following_error(const ConfigReader& r) {
  return read_declared_generator<FollowingErrorGenerator>(r, following_error_fields());
}

}  // namespace cnclab
