#pragma once
// TttrrOptions from YAML (configs/machines/tttrr_*.yaml) and back. Angles are
// degrees in YAML, radians inside:
//   offset_d: 100            # mm
//   limits: {x: [-400, 400], y: [-300, 300], z: [-300, 300],   # mm
//            a: [-110, 110], c: [-180, 180]}                    # deg
//   c_at_singularity: 0      # deg
//   singular_tolerance: 1e-12
//   unit_tolerance: 1e-9
#include <string>
#include <utility>

#include "cnclab/core/config.hpp"
#include "cnclab/core/fields.hpp"
#include "cnclab/kinematics/tttrr.hpp"

namespace cnclab {

// Reads `key` as [min, max] (min < max) times `unit` over `fallback`.
JointRange read_joint_range(const ConfigReader& r, const std::string& key,
                            const JointRange& fallback, double unit);
// [min / unit, max / unit] as a flow list of shortest round-trip numbers.
YAML::Node joint_range_node(const JointRange& range, double unit);

// `list` with a JointRange member declared as `key`: [min, max] in the YAML's
// units, the member's = YAML's * `unit` (1 for mm; pi/180 for degrees).
template <class S>
FieldList<S> with_joint_range(FieldList<S> list, std::string key, JointRange S::*member,
                              double unit, std::string doc) {
  FieldInfo info = custom_info(key, std::move(doc), FieldKind::number_list);
  info.items = 2;
  std::move(list).custom(
      info,
      [key, member, unit](const ConfigReader& r, S& s) {
        s.*member = read_joint_range(r, key, s.*member, unit);
      },
      [member, unit](const S& s) { return joint_range_node(s.*member, unit); });
  return list;
}

// machine: of `ik_samples` and configs/machines/tttrr_*.yaml.
const FieldList<TttrrOptions>& tttrr_fields();

// Strict: unknown keys and bad values are ConfigErrors naming the position.
TttrrOptions read_tttrr_options(const ConfigReader& machine);

// The resolved options as a YAML block map that read_tttrr_options() reads
// back to the same values (degrees converted exactly as written).
std::string tttrr_options_yaml(const TttrrOptions& options);

}  // namespace cnclab
