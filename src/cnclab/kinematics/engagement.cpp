#include "cnclab/kinematics/engagement.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <utility>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

constexpr double kFullCircle = 2.0 * std::numbers::pi;
constexpr double kSamePosition = 1e-12;  // mm: closer centres count as the same position

// Measure of the union of arcs [a, b] given with a in [0, 2 pi), b - a <= 2 pi.
double union_measure(std::vector<std::pair<double, double>>& arcs) {
  std::vector<std::pair<double, double>> flat;
  for (const auto& [a, b] : arcs) {
    if (b > kFullCircle) {
      flat.emplace_back(a, kFullCircle);
      flat.emplace_back(0.0, b - kFullCircle);
    } else {
      flat.emplace_back(a, b);
    }
  }
  std::sort(flat.begin(), flat.end());
  double total = 0, lo = 0, hi = -1;
  for (const auto& [a, b] : flat) {
    if (a > hi) {
      if (hi > lo) total += hi - lo;
      lo = a;
      hi = b;
    } else {
      hi = std::max(hi, b);
    }
  }
  if (hi > lo) total += hi - lo;
  return std::min(total, kFullCircle);
}

}  // namespace

std::vector<EngagementSample> engagement_angles(std::span<const Eigen::Vector2d> centres,
                                                double radius, std::size_t stride) {
  if (!(radius > 0) || !std::isfinite(radius)) {
    throw Error("engagement: tool radius must be a finite number > 0");
  }
  if (stride < 1) throw Error("engagement: stride must be at least 1");
  // Earlier positions within 2r of c_k lie in the 3 x 3 cells of side 2r
  // around c_k's cell; each cell lists its positions in path order.
  const double cell = 2 * radius;
  const auto key = [&](const Eigen::Vector2d& c) {
    return std::pair<long long, long long>{static_cast<long long>(std::floor(c.x() / cell)),
                                           static_cast<long long>(std::floor(c.y() / cell))};
  };
  std::map<std::pair<long long, long long>, std::vector<std::size_t>> cells;
  std::vector<EngagementSample> out;
  std::vector<std::pair<double, double>> arcs;
  for (std::size_t k = 0; k < centres.size(); ++k) {
    if (!centres[k].allFinite()) {
      throw Error("engagement: position " + std::to_string(k) + " is not finite");
    }
    const auto [cx, cy] = key(centres[k]);
    if (k % stride == 0) {
      arcs.clear();
      bool repeated = false;
      for (long long dx = -1; dx <= 1 && !repeated; ++dx) {
        for (long long dy = -1; dy <= 1 && !repeated; ++dy) {
          const auto it = cells.find({cx + dx, cy + dy});
          if (it == cells.end()) continue;
          for (std::size_t j : it->second) {
            const Eigen::Vector2d v = centres[j] - centres[k];
            const double d = v.norm();
            if (d < kSamePosition) {
              repeated = true;
              break;
            }
            if (d >= 2 * radius) continue;
            const double h = std::acos(d / (2 * radius));
            double a = std::atan2(v.y(), v.x()) - h;
            while (a < 0) a += kFullCircle;
            arcs.emplace_back(a, a + 2 * h);
          }
        }
      }
      out.push_back({k, repeated ? 0.0 : kFullCircle - union_measure(arcs)});
    }
    cells[{cx, cy}].push_back(k);
  }
  return out;
}

std::vector<Eigen::Vector2d> densify(std::span<const Eigen::Vector2d> points, double spacing,
                                     std::vector<std::size_t>* segment_of) {
  if (!(spacing > 0) || !std::isfinite(spacing)) {
    throw Error("densify: spacing must be a finite number > 0");
  }
  std::vector<Eigen::Vector2d> out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (i == 0) {
      out.push_back(points[0]);
      if (segment_of) segment_of->assign(1, 0);
      continue;
    }
    const Eigen::Vector2d a = points[i - 1], b = points[i];
    const auto pieces =
        static_cast<std::size_t>(std::max(1.0, std::ceil((b - a).norm() / spacing)));
    for (std::size_t k = 1; k <= pieces; ++k) {
      out.push_back(a + (b - a) * (static_cast<double>(k) / static_cast<double>(pieces)));
      if (segment_of) segment_of->push_back(i);
    }
  }
  return out;
}

}  // namespace cnclab
