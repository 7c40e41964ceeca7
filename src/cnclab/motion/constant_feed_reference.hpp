#pragma once
// The 1 ms reference of a constant-feed S-curve profile (feedrate_bounds.hpp,
// ConstantFeedrateProfile): the path speed follows the 7-phase S-curve in
// arc length (scurve.hpp) with cruise feed F, ramp acceleration a_t and jerk
// j_t, the path parameter u(s) by inverting the arc length. What a CNC does
// with one programmed feed and no look-ahead slow-down; the contour-error
// study's constant-feed baseline.
#include "cnclab/motion/feedrate_bounds.hpp"
#include "cnclab/motion/interpolator.hpp"

namespace cnclab {

// Samples k = 0..K, K = ceil(profile.time / period), the last at rest at the
// path end. Axis derivatives by the chain rule from s(t) (v = s', a = s'',
// j = s''') and sigma = |C'|: u' = v / sigma, u'' = (a - (T.C'') u'^2) / sigma,
// u''' = (j - (T'.C'' + T.C''') u'^3 - 3 (T.C'') u' u'') / sigma with
// T = C'/sigma, T' = (C'' - T (T.C'')) / sigma (derivatives of s = integral
// of sigma du), then q' = C' u' etc. as interpolate() does. Throws
// cnclab::Error for a profile with non-positive feed, acceleration or jerk.
ReferenceTrajectory constant_feed_reference(const PlanarPath& path,
                                            const ConstantFeedrateProfile& profile,
                                            double period = 1e-3);

}  // namespace cnclab
