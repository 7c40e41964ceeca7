#pragma once
// Radial engagement of a cylindrical cutter along a 2-D tool path: the angle
// of the cutter's circumference in contact with stock, where the stock is the
// plane minus everything earlier tool positions removed (exact disc
// geometry, no grid).
//
// At position k (centre c_k, radius r) the periphery point at angle theta lies
// inside an earlier disc j (|c_j - c_k| = d < 2r) iff theta is within
// h = acos(d / (2r)) of the direction of c_j - c_k; the engagement is
// 2 pi minus the measure of the union of those arcs. Position 0 (plunge into
// full stock) has 2 pi. A position equal to an earlier one has 0.
//
// Closed forms (tests): straight slotting with spacing s gives
// pi + 2 asin(s / (2r)) -> pi (180 deg) as s -> 0; a straight pass beside an
// earlier parallel one at radial depth a_e gives acos(1 - a_e / r) +
// asin(s / (2r)).
#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <vector>

namespace cnclab {

struct EngagementSample {
  std::size_t index = 0;  // position in the path
  double angle = 0;       // engagement [rad], in [0, 2 pi]
};

// Engagement at positions 0, stride, 2 stride, ... (every position's disc is
// removed; stride only thins where the angle is evaluated). radius > 0,
// stride >= 1.
std::vector<EngagementSample> engagement_angles(std::span<const Eigen::Vector2d> centres,
                                                double radius, std::size_t stride = 1);

// The path resampled so that consecutive points are at most `spacing` apart
// (straight segments between the given points): the discrete positions
// overestimate the engagement by up to 2 asin(spacing / (2r)).
// segment_of (optional): for each output point, the index i of the input
// point it ends the segment towards (0 for the first point).
std::vector<Eigen::Vector2d> densify(std::span<const Eigen::Vector2d> points, double spacing,
                                     std::vector<std::size_t>* segment_of = nullptr);

}  // namespace cnclab
