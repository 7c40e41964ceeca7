#include "cnclab/motion/contour_error.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}
Vec2 left_normal(const Vec2& t) {
  return Vec2(-t.y(), t.x());
}

// g(u) = C'(u).(C(u) - P) = (1/2) d/du |C(u) - P|^2 and its derivative.
struct DistanceSlope {
  double g, dg;
};
DistanceSlope slope(const PlanarPath& path, const Vec2& p, double u) {
  const PathPoint c = path.evaluate(u);
  const Vec2 r = c.position - p;
  return {c.d1.dot(r), c.d1.squaredNorm() + c.d2.dot(r)};
}

double distance_at(const PlanarPath& path, const Vec2& p, double u) {
  return (path.evaluate(u).position - p).norm();
}

// Root of g in [lo, hi] with g(lo) < 0 < g(hi): Newton from `start`,
// bisection whenever Newton leaves the bracket or stalls.
double safeguarded_newton(const PlanarPath& path, const Vec2& p, double lo, double hi, double start,
                          const ProjectionOptions& o) {
  double u = std::clamp(start, lo, hi);
  const double tol = o.tolerance * (hi - lo);
  for (int it = 0; it < o.max_iterations; ++it) {
    const DistanceSlope s = slope(path, p, u);
    if (s.g == 0.0) return u;
    (s.g < 0 ? lo : hi) = u;
    double next = s.dg > 0 ? u - s.g / s.dg : lo - 1.0;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - u) <= tol || hi - lo <= tol) return next;
    u = next;
  }
  return u;
}

}  // namespace

PathFrame path_frame(const PathPoint& point) {
  PathFrame f;
  const double speed = point.d1.norm();
  f.tangent = point.d1 / speed;
  const double z = cross(point.d1, point.d2);  // C' x C'' = (0, 0, z)
  f.curvature = std::abs(z) / (speed * speed * speed);
  // b = sign(z) e_z; b x C' = sign(z) (-C'_y, C'_x): the left normal for a
  // left turn, the right normal for a right turn.
  const Vec2 left = left_normal(f.tangent);
  f.normal = z < 0 ? Vec2(-left) : left;
  return f;
}

void ProjectionOptions::validate() const {
  auto bad = [](const char* field, double v, const char* rule) {
    std::ostringstream s;
    s << v;
    throw OptionError(field, s.str(), rule);
  };
  if (!(window_factor > 0)) bad("window_factor", window_factor, "must be > 0");
  if (!(min_window > 0)) bad("min_window", min_window, "must be > 0");
  if (!(max_window >= min_window)) bad("max_window", max_window, "must be >= min_window");
  if (samples < 2) bad("samples", samples, "must be >= 2");
  if (!(tolerance > 0)) bad("tolerance", tolerance, "must be > 0");
  if (max_iterations < 1) bad("max_iterations", max_iterations, "must be >= 1");
}

Projection project_to_path(const PlanarPath& path, const Vec2& actual, double u_ref,
                           const ProjectionOptions& o) {
  o.validate();
  const double u_min = path.u_begin(), u_max = path.u_end();
  const double u0 = std::clamp(u_ref, u_min, u_max);
  const PathPoint r = path.evaluate(u0);
  const double speed = r.d1.norm();
  double window = std::max(o.window_factor * (actual - r.position).norm(), o.min_window);
  for (;;) {
    const double lo_u = std::max(u_min, u0 - window / speed);
    const double hi_u = std::min(u_max, u0 + window / speed);
    // Sign changes of g on the samples; keep the one nearest to u_ref.
    double best_lo = 0, best_hi = 0, best_gap = INFINITY;
    double prev_u = lo_u, prev_g = slope(path, actual, lo_u).g;
    for (int k = 1; k <= o.samples; ++k) {
      const double u = lo_u + (hi_u - lo_u) * k / o.samples;
      const double g = slope(path, actual, u).g;
      if (prev_g < 0 && g >= 0) {
        const double gap = u0 < prev_u ? prev_u - u0 : u0 > u ? u0 - u : 0.0;
        if (gap < best_gap) best_gap = gap, best_lo = prev_u, best_hi = u;
      }
      prev_u = u;
      prev_g = g;
    }
    Projection out;
    if (std::isfinite(best_gap)) {
      out.u = safeguarded_newton(path, actual, best_lo, best_hi, u0, o);
    } else {
      // Monotone distance over the window: the minimum is at an end.
      out.u = distance_at(path, actual, lo_u) <= distance_at(path, actual, hi_u) ? lo_u : hi_u;
      const bool at_path_end = out.u == u_min || out.u == u_max;
      if (!at_path_end && window < o.max_window) {
        window = std::min(2 * window, o.max_window);
        continue;
      }
    }
    out.foot = path.evaluate(out.u).position;
    out.distance = (actual - out.foot).norm();
    return out;
  }
}

double taylor_contour_error(const PathPoint& reference, const Vec2& actual) {
  const PathFrame f = path_frame(reference);
  const Vec2 e = reference.position - actual;  // following error R - P
  const double et = e.dot(f.tangent);
  const Vec2 c = e - et * f.tangent;  // Eq. 4 numerator
  // Eq. 4's denominator, corrected: sqrt(|e|^2 - (e.t)^2) = |c|, taken as
  // |c| directly. The difference of squares cancels when e is almost
  // tangent: at |e| / |c| = 4800 it lost 4e-9 of |c|, which c^.n carried
  // into the curvature term (1.5e-11 mm on a 2 um estimate).
  const double c_norm = c.norm();
  const Vec2 c_hat = c_norm > 0 ? Vec2(c / c_norm) : f.normal;
  const double k = f.curvature;
  // Eq. 3's denominator as 1 + kappa (c.n) = 1 - kappa b, b = (P - R).n the
  // offset of P towards the centre of curvature (contour_error.hpp says why
  // the printed minus sign is not used with c from e = R - P).
  return -c_hat.dot(e) - 0.5 * k * c_hat.dot(f.normal) * et * et / (1.0 + k * c.dot(f.normal));
}

double tangent_line_contour_error(const PathPoint& reference, const Vec2& actual) {
  const Vec2 t = reference.d1.normalized();
  const Vec2 e = reference.position - actual;
  return (e - e.dot(t) * t).norm();
}

double osculating_circle_contour_error(const PathPoint& reference, const Vec2& actual) {
  const PathFrame f = path_frame(reference);
  if (f.curvature == 0.0) return tangent_line_contour_error(reference, actual);
  const double radius = 1.0 / f.curvature;
  const Vec2 centre = reference.position + radius * f.normal;
  return std::abs((actual - centre).norm() - radius);
}

ContourErrorComparison compare_contour_estimates(const PlanarPath& path,
                                                 const ReferenceTrajectory& reference,
                                                 const Eigen::MatrixX2d& actual,
                                                 const ProjectionOptions& options) {
  const Eigen::Index n = reference.samples();
  if (actual.rows() != n) {
    std::ostringstream m;
    m << "compare_contour_estimates: " << actual.rows() << " actual positions for " << n
      << " reference samples";
    throw Error(m.str());
  }
  ContourErrorComparison out;
  out.exact.resize(static_cast<std::size_t>(n));
  auto add = [](EstimateDiscrepancy& d, double estimate, double exact) {
    const double diff = std::abs(estimate - exact);
    d.mean += diff;
    d.max = std::max(d.max, diff);
  };
  for (Eigen::Index k = 0; k < n; ++k) {
    const Vec2 p = actual.row(k).transpose();
    const double exact = project_to_path(path, p, reference.u[k], options).distance;
    const PathPoint ref = path.evaluate(reference.u[k]);
    out.exact[k] = exact;
    add(out.taylor, std::abs(taylor_contour_error(ref, p)), exact);
    add(out.tangent_line, tangent_line_contour_error(ref, p), exact);
    add(out.osculating_circle, osculating_circle_contour_error(ref, p), exact);
  }
  for (EstimateDiscrepancy* d : {&out.taylor, &out.tangent_line, &out.osculating_circle}) {
    d->mean /= std::max<Eigen::Index>(n, 1);
  }
  return out;
}

}  // namespace cnclab
