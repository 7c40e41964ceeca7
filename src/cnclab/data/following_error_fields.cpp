// The declared options of the `following_error` generator (one FieldList:
// reader, emitter, identity text and JSON Schema) and its reader.
#include "cnclab/core/error.hpp"
#include "cnclab/data/declared_generator.hpp"
#include "cnclab/data/following_error.hpp"
#include "cnclab/data/named_config_file.hpp"
#include "cnclab/motion/machine_fields.hpp"

namespace cnclab {
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
  using D = AxisDirectionOptions;
  static const auto direction =
      FieldList<D>()
          .field("deadband", &D::deadband, "|v| at or below this is standstill [mm/s]",
                 Rule::non_negative())
          .field("reversal_time_constant", &D::reversal_time_constant,
                 "tau of the reversal pulse d exp(-(t - t_c) / tau) [s]", Rule::positive());
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
               "samples kept from the start (seed 002: over 170000); 0: the whole run; with "
               "feed_factors, the part of the path these samples of the plan cover")
        .field("feed_factors", &O::feed_factors,
               "time-scaled runs of the plan (factors in (0, 1]; 1 = the plan), each split at "
               "its time midpoint: first halves train, second halves validate; empty: seed "
               "002's single run")
        .omit_default()
        .field("extra_inputs", &O::extra_inputs,
               "direction features added as inputs <name>_x, <name>_y after v_x, v_y: sign, "
               "direction, reversal (motion/axis_direction.hpp)")
        .omit_default()
        .section("direction", &O::direction, direction,
                 "the direction features' deadband and reversal time constant")
        .omit_default()
        .field("plan_length", &O::plan_length,
               "plan the path in consecutive pieces of about this arc length [mm], each from "
               "rest to rest; 0: in one plan (seed 002)",
               Rule::non_negative())
        .omit_default();
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
