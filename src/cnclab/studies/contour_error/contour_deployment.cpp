#include "cnclab/studies/contour_error/contour_deployment.hpp"

#include <cmath>

#include "cnclab/core/error.hpp"
#include "cnclab/data/following_error.hpp"
#include "cnclab/deploy/sequence_extension.hpp"
#include "cnclab/motion/contour_error.hpp"

namespace cnclab {
namespace {

const char* const kContext[] = {"ref_x", "ref_y", "d1_x", "d1_y", "d2_x", "d2_y"};

int axis_index(const std::string& axis) {
  return axis == "x" ? 0 : axis == "y" ? 1 : -1;
}

// The networks are x then y: the contour estimate takes out[] as it comes.
bool planar(const DeployedModel& m) {
  return m.networks.size() == 2 && m.networks[0].axis == "x" && m.networks[1].axis == "y";
}

std::string unit_of(const Dataset& d, const std::string& name) {
  const Eigen::Index row = d.metadata_row(name);
  if (row < 0) throw ConfigError("following_error dataset without metadata column " + name);
  return d.metadata_units[static_cast<std::size_t>(row)];
}

void physical_columns(const Dataset& training, DeployedModel& m) {
  const FollowingErrorRanges ranges = following_error_ranges(training);
  for (const NarxNetwork& net : m.networks) {
    const int i = axis_index(net.axis);
    if (i < 0) {
      throw ConfigError(m.result_file + ": network '" + net.axis +
                        "' is neither x nor y of the following_error dataset");
    }
    const auto a = static_cast<std::size_t>(i);
    const std::string v = "v_ref_" + net.axis, e = "e_ref_" + net.axis;
    m.physical_inputs.push_back(
        {v, unit_of(training, v), ranges.velocity[a].min, ranges.velocity[a].max});
    m.physical_targets.push_back(
        {e, unit_of(training, e), ranges.following_error[a].min, ranges.following_error[a].max});
  }
}

std::vector<NamedColumn> per_tick(const DeployedModel& m,
                                  const std::map<std::string, Eigen::VectorXd>& context,
                                  const std::vector<Eigen::VectorXd>& predicted,
                                  const std::string& label) {
  if (label == "measured") {
    const auto exact = context.find("contour_exact");
    if (exact == context.end()) return {};
    return {{"contour_error.measured", "µm", exact->second}};
  }
  if (!planar(m)) return {};
  for (const char* name : kContext) {
    if (context.count(name) == 0) return {};
  }
  const auto& c = [&](const char* name) -> const Eigen::VectorXd& { return context.at(name); };
  Eigen::VectorXd out(predicted[0].size());
  for (Eigen::Index t = 0; t < out.size(); ++t) {
    PathPoint p;
    p.position = {c("ref_x")[t], c("ref_y")[t]};
    p.d1 = {c("d1_x")[t], c("d1_y")[t]};
    p.d2 = {c("d2_x")[t], c("d2_y")[t]};
    // As narx_metrics.cpp's contour_rms: e [µm] -> mm, |eps_c| -> µm.
    const Vec2 e_mm = {predicted[0][t] / 1000.0, predicted[1][t] / 1000.0};
    out[t] = std::abs(taylor_contour_error(p, p.position - e_mm)) * 1000.0;
  }
  return {{"contour_error." + label, "µm", out}};
}

// taylor_contour_error (motion/contour_error.cpp) and path_frame in C, term
// by term, from NAME_step's out[] (µm). In double the tool position is
// formed and subtracted again, as the contour_rms metric does (to its
// rounding); in float R - (R - e) would lose e's digits to R's magnitude,
// so e is taken as it is.
std::string c_definitions(const CCodeContext& c) {
  const std::string R = c.real(), L0 = c.literal(0), L1 = c.literal(1);
  const std::string sqrt = c.math("sqrt"), fabs = c.math("fabs"), k1000 = c.literal(1000);
  const bool as_metric = c.precision == CPrecision::float64;
  std::string e = as_metric ? "  ax = position[0] - error[0] / " + k1000 +
                                  ";  /* P = R - e [mm] */\n"
                                  "  ay = position[1] - error[1] / " +
                                  k1000 +
                                  ";\n"
                                  "  ex = position[0] - ax;  /* e = R - P, as the estimate "
                                  "takes it */\n  ey = position[1] - ay;\n"
                            : "  ex = error[0] / " + k1000 +
                                  ";  /* e = R - P [mm] */\n"
                                  "  ey = error[1] / " +
                                  k1000 + ";\n";
  return "\nint " + c.name + "_contour_error(const " + R + " position[2], const " + R +
         " d1[2], const " + R + " d2[2],\n    const " + R + " error[2], " + R +
         " *contour)\n{\n  " + R + (as_metric ? " ax, ay," : "") +
         " ex, ey, speed, tx, ty, z, k, nx, ny, et, cx, cy, cn, hx, hy, eps;\n"
         "  int i;\n  for (i = 0; i < 2; ++i) {\n"
         "    if (!isfinite(position[i]) || !isfinite(d1[i]) || !isfinite(d2[i]) ||\n"
         "        !isfinite(error[i])) return -1;\n  }\n"
         "  if (d1[0] * d1[0] + d1[1] * d1[1] == " +
         L0 + ") return -2;\n" + e + "  speed = " + sqrt +
         "(d1[0] * d1[0] + d1[1] * d1[1]);\n"
         "  tx = d1[0] / speed;\n  ty = d1[1] / speed;\n"
         "  z = d1[0] * d2[1] - d1[1] * d2[0];  /* C' x C'' (Eq. 5) */\n"
         "  k = " +
         fabs +
         "(z) / (speed * speed * speed);\n"
         "  nx = -ty;  /* n: the left normal for a left turn (Eq. 6) */\n  ny = tx;\n"
         "  if (z < " +
         L0 +
         ") {\n    nx = -nx;\n    ny = -ny;\n  }\n"
         "  et = ex * tx + ey * ty;\n  cx = ex - et * tx;  /* Eq. 4: c = e - (e.t) t */\n"
         "  cy = ey - et * ty;\n  cn = " +
         sqrt +
         "(cx * cx + cy * cy);\n"
         "  if (cn > " +
         L0 +
         ") {\n    hx = cx / cn;\n    hy = cy / cn;\n  } else {\n"
         "    hx = nx;\n    hy = ny;\n  }\n"
         "  /* Eq. 3 with the denominator 1 + kappa (c.n) (motion/contour_error.hpp) */\n"
         "  eps = -(hx * ex + hy * ey) -\n        " +
         c.literal(0.5) + " * k * (hx * nx + hy * ny) * et * et / (" + L1 +
         " + k * (cx * nx + cy * ny));\n"
         "  *contour = " +
         fabs + "(eps) * " + k1000 + ";\n  return 0;\n}\n";
}

std::string torch_methods() {
  return R"(
    def contour_error(self, position, d1, d2, error):
        """Seed 002 Eqs. 3-6: |eps_c| [um] of the tool position P = R - error
        (error [um] as forward() gives it, R = position, d1 = C'(u), d2 = C''(u)
        [mm]; tensors (batch, 2)) -> (batch,)."""
        actual = position - error / 1000.0
        e = position - actual
        speed = torch.sqrt(d1[..., 0] * d1[..., 0] + d1[..., 1] * d1[..., 1])
        t = d1 / speed.unsqueeze(-1)
        z = d1[..., 0] * d2[..., 1] - d1[..., 1] * d2[..., 0]
        k = torch.abs(z) / (speed * speed * speed)
        left = torch.stack([-t[..., 1], t[..., 0]], dim=-1)
        n = torch.where((z < 0).unsqueeze(-1), -left, left)
        et = e[..., 0] * t[..., 0] + e[..., 1] * t[..., 1]
        c = e - et.unsqueeze(-1) * t
        cn = torch.sqrt(c[..., 0] * c[..., 0] + c[..., 1] * c[..., 1])
        h = torch.where((cn > 0).unsqueeze(-1), c / cn.unsqueeze(-1), n)
        eps = -(h[..., 0] * e[..., 0] + h[..., 1] * e[..., 1]) - 0.5 * k * (
            h[..., 0] * n[..., 0] + h[..., 1] * n[..., 1]) * et * et / (
            1.0 + k * (c[..., 0] * n[..., 0] + c[..., 1] * n[..., 1]))
        return torch.abs(eps) * 1000.0
)";
}

ExtraCode code(const DeployedModel& m, const CCodeContext& c) {
  if (!planar(m) || !m.has_physical_columns()) {
    return {"", "", "", {"contour     no contour error estimate: it needs networks x and y"}};
  }
  ExtraCode x;
  x.description = {
      "contour     " + c.name + "_contour_error: seed 002's Taylor estimate (Eqs. 3-6) of",
      "            the contour error [um] from out[] and the interpolator's R, C'(u), C''(u)"};
  x.c_declarations =
      "/* Seed 002 Eqs. 3-6, the Taylor contour error estimate: *contour = |eps_c| [um]\n"
      "   at the tool position P = position - error / 1000 for the following errors\n"
      "   error[] [um] (" +
      c.name +
      "_step's out: x, y), the reference point position = C(u)\n"
      "   [mm] and the path derivatives d1 = C'(u), d2 = C''(u) of the interpolator. 0,\n"
      "   -1 when an input is NaN or infinite, -2 when d1 = 0 (no tangent). */\n"
      "int " +
      c.name + "_contour_error(const " + c.real() + " position[2], const " + c.real() +
      " d1[2], const " + c.real() + " d2[2],\n    const " + c.real() + " error[2], " + c.real() +
      " *contour);\n";
  x.c_definitions = c_definitions(c);
  x.torch_methods = torch_methods();
  return x;
}

}  // namespace

void register_contour_deployment() {
  SequenceExtension e;
  e.generator = "following_error";
  e.owner = "contour_error (seed 002)";
  e.physical_columns = physical_columns;
  for (const char* name : kContext) e.context_columns.emplace_back(name, "mm");
  e.context_columns.emplace_back("contour_exact", "µm");
  e.per_tick = per_tick;
  e.code = code;
  register_sequence_extension(std::move(e));
}

}  // namespace cnclab
