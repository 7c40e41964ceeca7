#include "cnclab/kinematics/tttrr_config.hpp"

#include <numbers>
#include <vector>

#include "cnclab/core/format.hpp"

namespace cnclab {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

}  // namespace

JointRange read_joint_range(const ConfigReader& r, const std::string& key,
                            const JointRange& fallback, double unit) {
  if (!r.has(key)) return fallback;
  const auto v = r.require<std::vector<double>>(key);
  if (v.size() != 2) r.fail(key, "must be a list [min, max]");
  if (!(v[0] < v[1])) r.fail(key, "must have min < max");
  return {v[0] * unit, v[1] * unit};
}

YAML::Node joint_range_node(const JointRange& range, double unit) {
  YAML::Node n(YAML::NodeType::Sequence);
  n.push_back(YAML::Load(shortest_double(range.min / unit)));
  n.push_back(YAML::Load(shortest_double(range.max / unit)));
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

const FieldList<TttrrOptions>& tttrr_fields() {
  using M = TttrrOptions;
  static const auto limits = [] {
    FieldList<M> f;
    for (const auto& [key, member] : {std::pair{"x", &M::x}, {"y", &M::y}, {"z", &M::z}}) {
      f = with_joint_range(std::move(f), key, member, 1.0, std::string(key) + " travel [mm]");
    }
    f = with_joint_range(std::move(f), "a", &M::a, kRadPerDeg,
                         "A travel [deg], inside [-180, 180]");
    return with_joint_range(std::move(f), "c", &M::c, kRadPerDeg,
                            "C travel [deg]; may span more than one turn");
  }();
  static const auto fields =
      FieldList<M>()
          .field("offset_d", &M::offset_d,
                 "d, A axis to workpiece origin along C [mm] (seed 004 Table 1; value ours)",
                 Rule::finite_number())
          .group("limits", limits, "axis travel, [min, max] with min < max")
          .custom(
              custom_info("c_at_singularity",
                          "C at the A = 0 singularity without a previous C [deg]",
                          FieldKind::number, Rule::finite_number()),
              [](const ConfigReader& r, M& m) {
                m.c_at_singularity =
                    r.get<double>("c_at_singularity", m.c_at_singularity / kRadPerDeg) * kRadPerDeg;
              },
              [](const M& m) {
                return YAML::Load(shortest_double(m.c_at_singularity / kRadPerDeg));
              })
          .field("singular_tolerance", &M::singular_tolerance,
                 "|sin A| at or below this is the A = 0 singularity",
                 Rule::in(0, false, 1e-3, false))
          .field("unit_tolerance", &M::unit_tolerance,
                 "largest accepted | |O| - 1 | of a pose's orientation vector",
                 Rule::in(0, false, 1e-3, false));
  return fields;
}

TttrrOptions read_tttrr_options(const ConfigReader& r) {
  TttrrOptions m;
  tttrr_fields().read(r, m);
  r.validate([&] { m.validate(); });
  return m;
}

std::string tttrr_options_yaml(const TttrrOptions& m) {
  return tttrr_fields().yaml(m);
}

}  // namespace cnclab
