#pragma once
// Test paths and their feedrate plans (default options), planned once per
// test binary and shared by the tests that need them.
#include <map>
#include <memory>
#include <numbers>
#include <string>

#include "cnclab/motion/analytic_paths.hpp"
#include "cnclab/motion/feedrate_planner.hpp"

namespace cnclab::testing {

struct PlannedPath {
  std::unique_ptr<PlanarPath> path;
  FeedrateProfile profile;
};

// "circle" (r = 20, one turn), "bezier" (an S-shaped cubic), "epitrochoid"
// (0.3 turn of R1 = 100, R2 = 8, k = 7), "line" (150 x 40 mm).
inline const PlannedPath& planned_path(const std::string& name) {
  static std::map<std::string, PlannedPath> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second;
  PlannedPath p;
  if (name == "circle") {
    p.path = std::make_unique<CirclePath>(Vec2(0, 0), 20.0, 0.0, 2 * std::numbers::pi);
  } else if (name == "bezier") {
    p.path = std::make_unique<CubicBezierPath>(
        std::array<Vec2, 4>{Vec2(0, 0), Vec2(60, 80), Vec2(120, -60), Vec2(180, 20)});
  } else if (name == "epitrochoid") {
    p.path = std::make_unique<EpitrochoidPath>(Vec2(0, 0), 100, 8, 7, 0.3);
  } else {
    p.path = std::make_unique<LinePath>(Vec2(0, 0), Vec2(150, 40));
  }
  // Windows smaller than the default, so that these short paths span
  // several and the window junctions are tested.
  FeedratePlannerOptions o;
  o.window_intervals = 240;
  o.commit_intervals = 180;
  p.profile = plan_feedrate(*p.path, o);
  return cache.emplace(name, std::move(p)).first->second;
}

inline const char* const kPlannedPathNames[] = {"circle", "bezier", "epitrochoid", "line"};

}  // namespace cnclab::testing
