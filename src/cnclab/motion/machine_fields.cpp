#include "cnclab/motion/machine_fields.hpp"

namespace cnclab {
namespace {

// axes.x / axes.y: a std::array element is not a member, so each is a key
// read and emitted here with the feed-drive declarations as its children.
template <std::size_t Axis>
FieldInfo axis_info(const char* key) {
  FieldInfo i = custom_info(key, std::string("the ") + key + " feed drive", FieldKind::section);
  i.children = feed_drive_fields().info(MachineOptions{}.axes[Axis]);
  return i;
}

template <std::size_t Axis>
void read_axis(const ConfigReader& axes, const char* key, MachineOptions& m) {
  feed_drive_fields().read(axes.section(key), m.axes[Axis]);
}

}  // namespace

const FieldList<DriveTiming>& drive_timing_fields() {
  using T = DriveTiming;
  static const auto fields =
      FieldList<T>()
          .field("controller_period", &T::controller_period,
                 "position loop = interpolator period [s] (seed 002: 1 ms)", Rule::positive())
          .field("velocity_loop_period", &T::velocity_loop_period,
                 "drive velocity loop [s]; must divide controller_period", Rule::positive())
          .field("integration_step", &T::integration_step,
                 "mechanics integration step [s]; must divide velocity_loop_period",
                 Rule::positive());
  return fields;
}

const FieldList<FeedDriveOptions>& feed_drive_fields() {
  using F = FeedDriveOptions;
  static const auto fields =
      FieldList<F>()
          .field("motor_inertia", &F::motor_inertia, "J_motor [kg m^2]", Rule::non_negative())
          .field("screw_inertia", &F::screw_inertia, "J_screw [kg m^2]", Rule::non_negative())
          .field("table_mass", &F::table_mass, "m, moving mass [kg]; reflected as m (p / 2 pi)^2",
                 Rule::non_negative())
          .field("screw_lead", &F::screw_lead, "p, table travel per screw turn [mm]",
                 Rule::positive())
          .field("torque_limit", &F::torque_limit, "tau_max [N m]", Rule::positive())
          .field("viscous_friction", &F::viscous_friction, "b [N m s/rad]", Rule::non_negative())
          .field("coulomb_friction", &F::coulomb_friction, "tau_c [N m]; 0 = off",
                 Rule::non_negative())
          .field("static_friction", &F::static_friction,
                 "tau_s [N m], breakaway (>= coulomb_friction); 0 = off", Rule::non_negative())
          .field("stribeck_velocity", &F::stribeck_velocity, "w_s [rad/s]", Rule::positive())
          .field("backlash", &F::backlash, "g, total gap [mm]; 0 = off", Rule::non_negative())
          .field("lead_error_amplitude", &F::lead_error_amplitude,
                 "A_lead, ball-screw lead error [mm]; 0 = off", Rule::non_negative())
          .field("lead_error_phase", &F::lead_error_phase, "phi [rad]", Rule::finite_number())
          .field("position_gain", &F::position_gain, "Kp [1/s] (the Kv factor of CNC tuning)",
                 Rule::positive())
          .field("velocity_feedforward", &F::velocity_feedforward, "k_ff [-]",
                 Rule::in(0, true, 1, true))
          .field("velocity_gain", &F::velocity_gain, "Kv [N m s/rad]", Rule::positive())
          .field("velocity_integral_time", &F::velocity_integral_time, "Ti [s]", Rule::positive())
          .field("scale_resolution", &F::scale_resolution, "linear scale quantum [mm]; 0 = ideal",
                 Rule::non_negative())
          .field("scale_noise", &F::scale_noise,
                 "linear scale noise standard deviation [mm]; 0 = off", Rule::non_negative())
          .field("motor_encoder_counts", &F::motor_encoder_counts,
                 "counts per motor turn; 0 = ideal");
  return fields;
}

const FieldList<MachineOptions>& machine_fields() {
  using M = MachineOptions;
  static const auto axes =
      FieldList<M>()
          .custom(
              axis_info<0>("x"), [](const ConfigReader& r, M& m) { read_axis<0>(r, "x", m); },
              [](const M& m) { return feed_drive_fields().to_node(m.axes[0]); })
          .custom(
              axis_info<1>("y"), [](const ConfigReader& r, M& m) { read_axis<1>(r, "y", m); },
              [](const M& m) { return feed_drive_fields().to_node(m.axes[1]); });
  static const auto fields =
      FieldList<M>()
          .field("name", &M::name, "the machine's name, stated in results")
          .section("timing", &M::timing, drive_timing_fields(), "loop rates shared by both axes")
          .group("axes", axes, "the two feed drives");
  return fields;
}

}  // namespace cnclab
