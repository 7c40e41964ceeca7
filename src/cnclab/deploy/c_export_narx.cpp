// The narx model as C: one state struct with every network's delay lines,
// NAME_init (standstill) and NAME_step (one tick of every network), the
// arithmetic of nn/narx_predictor.cpp and Narx::step (nn/narx.cpp).
#include <sstream>

#include "cnclab/deploy/c_export_detail.hpp"
#include "cnclab/deploy/export_weights.hpp"

namespace cnclab::c_export_detail {
namespace {

// The columns' physical scaling (ColumnScaling) as constants and the C of
// scale_in(a, x) and scale_out(a, y); identity without physical columns.
std::string scaling_functions(const DeployedModel& m, const CCodeContext& c,
                              const ArrayWriter& array) {
  const std::string R = c.real(), p = c.name + "_";
  std::string out;
  std::string in = "x", inverse = "y";
  if (m.has_physical_columns()) {
    const NarxWeights w = narx_weights(m);
    const std::size_t n = m.networks.size();
    out +=
        "/* The dataset's scaling of each physical column (mapminmax to [-1, 1] over\n"
        "   [min, min + span] of the training data). */\n" +
        array("in_min", {n}, w.in_min) + array("in_span", {n}, w.in_span) +
        array("out_min", {n}, w.out_min) + array("out_span", {n}, w.out_span);
    in = "(x - " + p + "in_min[a]) / " + p + "in_span[a] * " + c.literal(2) + " - " + c.literal(1);
    inverse = p + "out_min[a] + (y + " + c.literal(1) + ") * " + c.literal(0.5) + " * " + p +
              "out_span[a]";
  }
  out += "\nstatic " + R + " " + p + "scale_in(int a, " + R + " x)\n{\n  (void)a;\n  return " + in +
         ";\n}\n\nstatic " + R + " " + p + "scale_out(int a, " + R +
         " y)\n{\n  (void)a;\n  return " + inverse + ";\n}\n\n";
  // The fed-back outputs live in the network's units: scale_out's inverse.
  if (m.has_physical_columns()) {
    out += "static " + R + " " + p + "unscale_out(int a, " + R + " x)\n{\n  return (x - " + p +
           "out_min[a]) / " + p + "out_span[a] * " + c.literal(2) + " - " + c.literal(1) +
           ";\n}\n\n";
  } else {
    out += "static " + R + " " + p + "unscale_out(int a, " + R +
           " x)\n{\n  (void)a;\n  return x;\n}\n\n";
  }
  return out;
}

}  // namespace

CExport narx_export(const DeployedModel& m, const CCodeContext& c,
                    const std::vector<std::string>& notes) {
  const NarxOptions& o = m.narx;
  const std::size_t nets = m.networks.size(), h = o.hidden, dv = o.input_delays,
                    de = o.feedback_delays, d0 = o.first_input_delay, n = dv + de;
  const std::string M = macro_prefix(c.name), R = c.real(), p = c.name + "_";
  const ExtraCode extra = m.extension && m.extension->code ? m.extension->code(m, c) : ExtraCode{};
  const std::vector<std::string> use = {
      p + "state s;  " + R + " in[" + M + "_NETWORKS], out[" + M + "_NETWORKS];",
      p + "init(&s);                  at standstill, before the first tick",
      "every tick: if (" + p + "step(&s, in, out) != 0) { ... a NaN or infinite input ... }"};

  CExport e;
  e.header = header_top(m, c, notes, extra, use);
  e.header += "#define " + M + "_NETWORKS " + std::to_string(nets) + "\n#define " + M +
              "_INPUT_HISTORY " + std::to_string(d0 + dv) + "\n#define " + M + "_FEEDBACK_DELAYS " +
              std::to_string(de) + "\n\n";
  e.header +=
      "/* The delay lines, newest first, in the networks' (scaled) units: v[a][k] the\n"
      "   input of network a k + 1 ticks ago (room for this tick's), e[a][k] its output. */\n"
      "typedef struct {\n  " +
      R + " v[" + M + "_NETWORKS][" + M + "_INPUT_HISTORY];\n  " + R + " e[" + M + "_NETWORKS][" +
      M + "_FEEDBACK_DELAYS];\n} " + p + "state;\n\n" +
      "/* Standstill: every past input and output the physical 0. */\nvoid " + p + "init(" + p +
      "state *s);\n" +
      "/* One tick: in[a] the input of network a now, out[a] its prediction fed back\n"
      "   (closed loop); 0, or -1 with s and out unchanged when an input is NaN or\n"
      "   infinite. */\nint " +
      p + "step(" + p + "state *s, const " + R + " in[" + M + "_NETWORKS], " + R + " out[" + M +
      "_NETWORKS]);\n" + extra.c_declarations + "\n#endif\n";

  const ArrayWriter array(c);
  const NarxWeights w = narx_weights(m);
  std::ostringstream s;
  s << source_top(c)
    << "/* Network a (seed 002 Eq. 1): h_i = sum_j w1[a][i][j] x_j + b1[a][i],\n"
       "   e = sum_i w2[a][i] f(h_i) + b2[a]; x = [v(t - d0 - j), j < D_V; e(t - k), k = 1..D_E]\n"
       "   with d0 = "
    << d0 << ", D_V = " << dv << ", D_E = " << de << ". */\n"
    << array("w1", {nets, h, n}, w.w1) << array("b1", {nets, h}, w.b1)
    << array("w2", {nets, h}, w.w2) << array("b2", {nets}, w.b2) << scaling_functions(m, c, array);
  s << "void " << p << "init(" << p << "state *s)\n{\n  int a, k;\n  for (a = 0; a < " << M
    << "_NETWORKS; ++a) {\n    for (k = 0; k < " << M << "_INPUT_HISTORY; ++k) s->v[a][k] = " << p
    << "scale_in(a, " << c.literal(0) << ");\n    for (k = 0; k < " << M
    << "_FEEDBACK_DELAYS; ++k) s->e[a][k] = " << p << "unscale_out(a, " << c.literal(0)
    << ");\n  }\n}\n\n";
  s << "int " << p << "step(" << p << "state *s, const " << R << " in[" << M << "_NETWORKS], " << R
    << " out[" << M << "_NETWORKS])\n{\n  " << R << " x[" << n << "], z, y;\n  int a, i, j, k;\n"
    << "  for (a = 0; a < " << M << "_NETWORKS; ++a) {\n    if (!isfinite(in[a])) return -1;\n  }\n"
    << "  for (a = 0; a < " << M << "_NETWORKS; ++a) {\n"
    << "    for (k = " << M << "_INPUT_HISTORY - 1; k > 0; --k) s->v[a][k] = s->v[a][k - 1];\n"
    << "    s->v[a][0] = " << p << "scale_in(a, in[a]);\n"
    << "    for (j = 0; j < " << dv << "; ++j) x[j] = s->v[a][" << d0 << " + j];\n"
    << "    for (k = 0; k < " << de << "; ++k) x[" << dv << " + k] = s->e[a][k];\n"
    << "    y = " << c.literal(0) << ";\n    for (i = 0; i < " << h
    << "; ++i) {\n      z = " << c.literal(0) << ";\n      for (j = 0; j < " << n
    << "; ++j) z += " << p << "w1[a][i][j] * x[j];\n      z += " << p
    << "b1[a][i];\n      y += " << p << "w2[a][i] * " << activation(o.hidden_activation, "z", c)
    << ";\n    }\n    y += " << p << "b2[a];\n"
    << "    for (k = " << M << "_FEEDBACK_DELAYS - 1; k > 0; --k) s->e[a][k] = s->e[a][k - 1];\n"
    << "    s->e[a][0] = y;\n    out[a] = " << p << "scale_out(a, y);\n  }\n  return 0;\n}\n"
    << extra.c_definitions;
  e.source = s.str();
  return e;
}

}  // namespace cnclab::c_export_detail
