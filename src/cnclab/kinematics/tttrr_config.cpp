#include "cnclab/kinematics/tttrr_config.hpp"

#include <numbers>
#include <vector>

#include "cnclab/core/format.hpp"

namespace cnclab {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

JointRange read_range(const ConfigReader& r, const std::string& key, const JointRange& fallback,
                      double unit) {
  if (!r.has(key)) return fallback;
  const auto v = r.require<std::vector<double>>(key);
  if (v.size() != 2) r.fail(key, "must be a list [min, max]");
  if (!(v[0] < v[1])) r.fail(key, "must have min < max");
  return {v[0] * unit, v[1] * unit};
}

std::string range_yaml(const JointRange& r, double unit) {
  std::string text = "[";  // built by appending: gcc 12 -Wrestrict misfires on "[" + string
  text += shortest_double(r.min / unit);
  text += ", ";
  text += shortest_double(r.max / unit);
  return text += "]";
}

}  // namespace

TttrrOptions read_tttrr_options(const ConfigReader& r) {
  TttrrOptions m;
  m.offset_d = r.get<double>("offset_d", m.offset_d);
  const ConfigReader l = r.section("limits");
  m.x = read_range(l, "x", m.x, 1.0);
  m.y = read_range(l, "y", m.y, 1.0);
  m.z = read_range(l, "z", m.z, 1.0);
  m.a = read_range(l, "a", m.a, kRadPerDeg);
  m.c = read_range(l, "c", m.c, kRadPerDeg);
  m.c_at_singularity =
      r.get<double>("c_at_singularity", m.c_at_singularity / kRadPerDeg) * kRadPerDeg;
  m.singular_tolerance = r.get<double>("singular_tolerance", m.singular_tolerance);
  m.unit_tolerance = r.get<double>("unit_tolerance", m.unit_tolerance);
  r.validate([&] { m.validate(); });
  return m;
}

std::string tttrr_options_yaml(const TttrrOptions& m) {
  return "offset_d: " + shortest_double(m.offset_d) + "\nlimits: {x: " + range_yaml(m.x, 1.0) +
         ", y: " + range_yaml(m.y, 1.0) + ", z: " + range_yaml(m.z, 1.0) +
         ", a: " + range_yaml(m.a, kRadPerDeg) + ", c: " + range_yaml(m.c, kRadPerDeg) +
         "}\nc_at_singularity: " + shortest_double(m.c_at_singularity / kRadPerDeg) +
         "\nsingular_tolerance: " + shortest_double(m.singular_tolerance) +
         "\nunit_tolerance: " + shortest_double(m.unit_tolerance) + "\n";
}

}  // namespace cnclab
