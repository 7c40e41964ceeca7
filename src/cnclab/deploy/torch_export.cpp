#include "cnclab/deploy/torch_export.hpp"

#include <sstream>

#include "cnclab/deploy/code_text.hpp"
#include "cnclab/deploy/export_weights.hpp"
#include "cnclab/deploy/sequence_extension.hpp"

namespace cnclab {
namespace {

constexpr int kValuesPerLine = 3;

std::string py_string(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '\\' || c == '"') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string py_strings(const std::vector<std::string>& items) {
  std::string out = "[";
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + py_string(items[i]);
  return out + "]";
}

// _values("0x1.8p+1 ..."): the exact doubles, kValuesPerLine a line.
std::string py_values(const std::vector<double>& v) {
  std::string out = "_values(\"\"\"";
  for (std::size_t i = 0; i < v.size(); ++i) {
    out += i % kValuesPerLine == 0 ? "\n    " : " ";
    out += hex_double(v[i]);
  }
  return out + "\"\"\")";
}

std::vector<double> values_of(const Eigen::VectorXd& v) {
  return {v.data(), v.data() + v.size()};
}

// f(z) of nn/activation.cpp in torch.
std::string activation(Activation f, const std::string& z) {
  switch (f) {
    case Activation::relu:
      return "torch.relu(" + z + ")";
    case Activation::tanh:
      return "torch.tanh(" + z + ")";
    case Activation::sigmoid:
      return "1.0 / (1.0 + torch.exp(-" + z + "))";
    case Activation::linear:
      break;
  }
  return z;
}

std::string docstring(const DeployedModel& m, const std::string& name,
                      const std::vector<std::string>& notes, const ExtraCode& extra,
                      const std::vector<std::string>& use) {
  std::vector<std::string> lines = {
      name +
          ".py: a network trained by cnclab, exported for PyTorch (cnclab export --format "
          "torch).",
      ""};
  const auto add = [&](const std::vector<std::string>& more) {
    lines.insert(lines.end(), more.begin(), more.end());
  };
  add(model_description(m));
  add(extra.description);
  add(notes);
  lines.push_back("");
  add(use);
  std::string out = "\"\"\"";
  for (const auto& l : lines) {
    std::string safe;
    for (const char c : l) safe += c == '\\' ? std::string("\\\\") : std::string(1, c);
    for (std::size_t at = safe.find("\"\"\""); at != std::string::npos; at = safe.find("\"\"\"")) {
      safe.replace(at, 3, "'''");
    }
    out += safe + "\n";
  }
  return out +
         "\"\"\"\n\nimport torch\n\n\ndef _values(text):\n"
         "    return [float.fromhex(t) for t in text.split()]\n\n\n";
}

std::string class_head(const DeployedModel& m, const std::string& name) {
  return "class " + name +
         "(torch.nn.Module):\n    INPUT_COLUMNS = " + py_strings(m.export_input_names()) +
         "\n    INPUT_UNITS = " + py_strings(m.export_input_units()) +
         "\n    OUTPUT_COLUMNS = " + py_strings(m.export_output_names()) +
         "\n    OUTPUT_UNITS = " + py_strings(m.export_output_units()) + "\n\n";
}

// The normalisation of nn/scaling.hpp as buffers (into `init`) and the
// expressions of x (forward) and of y (inverse).
struct TorchScaling {
  std::string forward = "x", inverse = "y";
};
TorchScaling scaling(const ScalingRecord& s, const std::string& side, std::ostringstream& init) {
  TorchScaling t;
  std::string& forward = t.forward;
  std::string& inverse = t.inverse;
  if (s.method == Scaling::zscore) {
    init << "        self.register_buffer(\"" << side << "_mean\", torch.tensor("
         << py_values(values_of(s.mean)) << ", dtype=dtype))\n"
         << "        self.register_buffer(\"" << side << "_std\", torch.tensor("
         << py_values(values_of(s.std)) << ", dtype=dtype))\n";
    forward = "(x - self." + side + "_mean) / self." + side + "_std";
    inverse = "y * self." + side + "_std + self." + side + "_mean";
  } else if (s.method == Scaling::minmax) {
    const MinMaxNormaliser n(s.min, s.max, s.y_min, s.y_max);
    init << "        self.register_buffer(\"" << side << "_offset\", torch.tensor("
         << py_values(values_of(n.offset())) << ", dtype=dtype))\n"
         << "        self.register_buffer(\"" << side << "_gain\", torch.tensor("
         << py_values(values_of(n.gain())) << ", dtype=dtype))\n";
    const std::string y_min = "float.fromhex(\"" + hex_double(s.y_min) + "\")";
    forward = "(x - self." + side + "_offset) * self." + side + "_gain + " + y_min;
    inverse = "(y - " + y_min + ") / self." + side + "_gain + self." + side + "_offset";
  }
  return t;
}

std::string mlp_module(const DeployedModel& m, const std::string& name) {
  std::ostringstream init;
  init << "    def __init__(self, dtype=torch.float64):\n        super().__init__()\n"
       << "        self.layers = torch.nn.ModuleList()\n";
  for (const DenseLayer& layer : mlp_layers(m)) {  // row-major, as torch.nn.Linear holds it
    init << "        layer = torch.nn.Linear(" << layer.inputs << ", " << layer.outputs
         << ", dtype=dtype)\n"
         << "        with torch.no_grad():\n            layer.weight.copy_(torch.tensor("
         << py_values(layer.weights) << ", dtype=dtype).reshape(" << layer.outputs << ", "
         << layer.inputs << "))\n"
         << "            layer.bias.copy_(torch.tensor(" << py_values(layer.biases)
         << ", dtype=dtype))\n"
         << "        self.layers.append(layer)\n";
  }
  const TorchScaling in_scaling = scaling(m.input_scaling, "in", init);
  const TorchScaling out_scaling = scaling(m.target_scaling, "out", init);
  std::ostringstream s;
  s << class_head(m, name) << init.str() << "\n"
    << "    def forward(self, x):\n        \"\"\"x (batch, inputs) -> (batch, outputs).\"\"\"\n"
    << "        a = " << in_scaling.forward << "\n        last = len(self.layers) - 1\n"
    << "        for i, layer in enumerate(self.layers):\n            z = layer(a)\n"
    << "            a = " << activation(m.mlp.output_activation, "z") << " if i == last else "
    << activation(m.mlp.hidden_activation, "z") << "\n"
    << "        y = a\n        return " << out_scaling.inverse << "\n";
  return s.str();
}

std::string narx_module(const DeployedModel& m, const std::string& name, const ExtraCode& extra) {
  const NarxOptions& o = m.narx;
  const std::size_t nets = m.networks.size(), h = o.hidden, dv = o.input_delays,
                    de = o.feedback_delays, d0 = o.first_input_delay, n = dv + de;
  const NarxWeights w = narx_weights(m);
  std::ostringstream s;
  s << class_head(m, name) << "    NETWORKS = " << nets << "\n    INPUT_HISTORY = " << d0 + dv
    << "\n    FIRST_INPUT_DELAY = " << d0 << "\n    INPUT_DELAYS = " << dv
    << "\n    FEEDBACK_DELAYS = " << de << "\n\n"
    << "    def __init__(self, dtype=torch.float64):\n        super().__init__()\n"
    << "        def p(values, *shape):\n            return torch.nn.Parameter(torch.tensor("
       "values, dtype=dtype).reshape(*shape))\n"
    << "        self.w1 = p(" << py_values(w.w1) << ", " << nets << ", " << h << ", " << n << ")\n"
    << "        self.b1 = p(" << py_values(w.b1) << ", " << nets << ", " << h << ")\n"
    << "        self.w2 = p(" << py_values(w.w2) << ", " << nets << ", " << h << ")\n"
    << "        self.b2 = p(" << py_values(w.b2) << ", " << nets << ")\n";
  std::string scale_in = "x", scale_out = "y", unscale_out = "x";
  if (m.has_physical_columns()) {
    for (const auto& [buffer, v] :
         {std::pair{"in_min", &w.in_min}, std::pair{"in_span", &w.in_span},
          std::pair{"out_min", &w.out_min}, std::pair{"out_span", &w.out_span}}) {
      s << "        self.register_buffer(\"" << buffer << "\", torch.tensor(" << py_values(*v)
        << ", dtype=dtype))\n";
    }
    scale_in = "(x - self.in_min) / self.in_span * 2.0 - 1.0";
    scale_out = "self.out_min + (y + 1.0) * 0.5 * self.out_span";
    unscale_out = "(x - self.out_min) / self.out_span * 2.0 - 1.0";
  }
  s << "\n    def scale_in(self, x):\n        return " << scale_in
    << "\n\n    def scale_out(self, y):\n        return " << scale_out
    << "\n\n    def unscale_out(self, x):\n        return " << unscale_out << "\n\n"
    << "    def initial_state(self, batch=1):\n"
    << "        \"\"\"Standstill: every past input and output the physical 0.\"\"\"\n"
    << "        zero = torch.zeros(batch, self.NETWORKS, dtype=self.w1.dtype)\n"
    << "        v = self.scale_in(zero).unsqueeze(-1).repeat(1, 1, self.INPUT_HISTORY)\n"
    << "        e = self.unscale_out(zero).unsqueeze(-1).repeat(1, 1, self.FEEDBACK_DELAYS)\n"
    << "        return v, e\n\n"
    << "    def forward(self, x, state):\n"
    << "        \"\"\"One tick: x (batch, networks) -> (y (batch, networks), new state).\"\"\"\n"
    << "        v, e = state\n"
    << "        v = torch.cat([self.scale_in(x).unsqueeze(-1), v[..., :-1]], dim=-1)\n"
    << "        d0 = self.FIRST_INPUT_DELAY\n"
    << "        r = torch.cat([v[..., d0:d0 + self.INPUT_DELAYS], e], dim=-1)\n"
    << "        z = torch.einsum(\"aij,baj->bai\", self.w1, r) + self.b1\n"
    << "        y = (self.w2 * " << activation(o.hidden_activation, "z") << ").sum(-1) + self.b2\n"
    << "        e = torch.cat([y.unsqueeze(-1), e[..., :-1]], dim=-1)\n"
    << "        return self.scale_out(y), (v, e)\n\n"
    << "    def simulate(self, xs):\n"
    << "        \"\"\"Closed loop from standstill: xs (ticks, batch, networks) -> the same "
       "shape.\"\"\"\n"
    << "        state = self.initial_state(xs.shape[1])\n        ys = []\n"
    << "        for x in xs:\n            y, state = self(x, state)\n            ys.append(y)\n"
    << "        return torch.stack(ys)\n"
    << extra.torch_methods;
  return s.str();
}

}  // namespace

std::string torch_export(const DeployedModel& m, const std::string& name,
                         const std::vector<std::string>& notes) {
  check_export_identifier(name);
  const CCodeContext c{name, CPrecision::float64};
  const ExtraCode extra = m.kind == ModelKind::narx && m.extension && m.extension->code
                              ? m.extension->code(m, c)
                              : ExtraCode{};
  std::vector<std::string> use = {
      "Use (float64; " + name + "(dtype=torch.float32) for float):",
      "    spec = importlib.util.spec_from_file_location(\"" + name + "\", \"" + name + ".py\")",
      "    module = importlib.util.module_from_spec(spec); "
      "spec.loader.exec_module(module)",
      "    model = module." + name + "()"};
  if (m.kind == ModelKind::mlp) {
    use.push_back("    y = model(x)      # x (batch, inputs) in INPUT_UNITS -> (batch, outputs)");
    return docstring(m, name, notes, extra, use) + mlp_module(m, name);
  }
  use.push_back("    state = model.initial_state(batch)   # standstill");
  use.push_back("    y, state = model(x, state)           # one tick, x (batch, networks)");
  return docstring(m, name, notes, extra, use) + narx_module(m, name, extra);
}

}  // namespace cnclab
