#include "cnclab/sweep/sweep_spec.hpp"

#include <charconv>
#include <cmath>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/override.hpp"
#include "cnclab/sweep/sweep_fields.hpp"

namespace cnclab {
namespace {

// A rule broken by a values text; the callers add where.
struct BadValues {
  std::string rule;
};

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return "";
  const auto e = s.find_last_not_of(" \t");
  return std::string(s.substr(b, e - b + 1));
}

// Splits at commas outside brackets, braces, parentheses and quotes.
std::vector<std::string> split_top_level(std::string_view text) {
  std::vector<std::string> parts;
  int depth = 0;
  char quote = 0;
  std::size_t start = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '\'' || c == '"') {
      quote = c;
    } else if (c == '[' || c == '{' || c == '(') {
      ++depth;
    } else if (c == ']' || c == '}' || c == ')') {
      --depth;
    } else if (c == ',' && depth == 0) {
      parts.push_back(trim(text.substr(start, i - start)));
      start = i + 1;
    }
  }
  parts.push_back(trim(text.substr(start)));
  return parts;
}

YAML::Node yaml_value(const std::string& item) {
  if (item.empty()) throw BadValues{"empty value in the list"};
  try {
    YAML::Node node = YAML::Load(item);
    if (!node.IsDefined() || node.IsNull()) throw BadValues{"value '" + item + "' is null"};
    return node;
  } catch (const YAML::Exception& e) {
    throw BadValues{"value '" + item + "' is not valid YAML: " + e.msg};
  }
}

double number(const std::string& text) {
  double v = 0;
  const char* b = text.data();
  const char* e = text.data() + text.size();
  if (b != e && *b == '+') ++b;
  const auto [ptr, ec] = std::from_chars(b, e, v);
  if (ec != std::errc() || ptr != e || b == e || !std::isfinite(v)) {
    throw BadValues{"'" + text + "' is not a finite number"};
  }
  return v;
}

std::int64_t integer(const std::string& text) {
  std::int64_t v = 0;
  const char* b = text.data();
  const char* e = text.data() + text.size();
  if (b != e && *b == '+') ++b;
  const auto [ptr, ec] = std::from_chars(b, e, v);
  if (ec != std::errc() || ptr != e || b == e) throw BadValues{"'" + text + "' is not an integer"};
  return v;
}

// name(args) with a known function name, or nullopt.
std::optional<SweepParameter> parse_function(const std::string& text) {
  const auto open = text.find('(');
  if (open == std::string::npos || text.back() != ')') return std::nullopt;
  const std::string name = trim(std::string_view(text).substr(0, open));
  for (char c : name) {
    if (!((c >= 'a' && c <= 'z') || c == '_')) return std::nullopt;
  }
  const std::string inner = text.substr(open + 1, text.size() - open - 2);
  const std::vector<std::string> args =
      trim(inner).empty() ? std::vector<std::string>{} : split_top_level(inner);
  SweepParameter p;
  if (name == "choice") {
    if (args.empty()) throw BadValues{"choice() needs at least one value"};
    for (const auto& a : args) p.values.push_back(yaml_value(a));
    return p;
  }
  if (name == "int_range") {
    if (args.size() != 2 && args.size() != 3) {
      throw BadValues{"int_range takes (first, last) or (first, last, step)"};
    }
    p.kind = SweepParameter::Kind::int_range;
    p.first = integer(args[0]);
    p.last = integer(args[1]);
    p.step = args.size() == 3 ? integer(args[2]) : 1;
    if (p.step < 1) throw BadValues{"int_range step must be at least 1"};
    if (p.first > p.last) throw BadValues{"int_range needs first <= last"};
    return p;
  }
  if (name == "uniform" || name == "log_uniform") {
    if (args.size() != 2) throw BadValues{name + " takes (low, high)"};
    p.kind = name == "uniform" ? SweepParameter::Kind::uniform : SweepParameter::Kind::log_uniform;
    p.low = number(args[0]);
    p.high = number(args[1]);
    if (!(p.low < p.high)) throw BadValues{name + " needs low < high"};
    if (p.kind == SweepParameter::Kind::log_uniform && p.low <= 0) {
      throw BadValues{"log_uniform needs 0 < low (a log range of non-positive numbers)"};
    }
    return p;
  }
  throw BadValues{"unknown function '" + name +
                  "' (known: choice, int_range, uniform, log_uniform)"};
}

// The grammar of sweep_spec.hpp; BadValues on a broken rule.
std::optional<SweepParameter> parse_values(const std::string& key, const std::string& text) {
  const std::string t = trim(text);
  if (t.empty()) throw BadValues{"empty list of values"};
  std::optional<SweepParameter> p = parse_function(t);
  if (!p) {
    const auto items = split_top_level(t);
    if (items.size() == 1) return std::nullopt;
    p.emplace();
    for (const auto& item : items) p->values.push_back(yaml_value(item));
  }
  p->key = key;
  p->text = t;
  return p;
}

// Each linked key follows the override key grammar.
void check_key(const std::string& key) {
  for (const auto& k : linked_keys(key)) parse_override(k + "=0");
}

YAML::Node scalar(const std::string& text) {
  return YAML::Load(text);
}

}  // namespace

std::vector<std::string> linked_keys(const std::string& key) {
  std::vector<std::string> keys;
  std::size_t start = 0;
  for (std::size_t plus = key.find('+'); plus != std::string::npos; plus = key.find('+', start)) {
    keys.push_back(key.substr(start, plus - start));
    start = plus + 1;
  }
  keys.push_back(key.substr(start));
  return keys;
}

std::vector<YAML::Node> SweepParameter::enumerate() const {
  if (kind == Kind::values) return values;
  std::vector<YAML::Node> out;
  if (kind == Kind::int_range) {
    for (std::int64_t v = first; v <= last; v += step) {
      out.push_back(scalar(std::to_string(v)));
      if (last - v < step) break;  // no overflow past `last`
    }
  }
  return out;
}

YAML::Node SweepParameter::sample(Rng& rng) const {
  switch (kind) {
    case Kind::values:
      return values[rng.below(values.size())];
    case Kind::int_range: {
      const auto count = static_cast<std::uint64_t>((last - first) / step) + 1;
      return scalar(std::to_string(first + static_cast<std::int64_t>(rng.below(count)) * step));
    }
    case Kind::uniform:
      return scalar(shortest_double(rng.uniform(low, high)));
    case Kind::log_uniform:
      return scalar(shortest_double(std::exp(rng.uniform(std::log(low), std::log(high)))));
  }
  return {};
}

std::optional<SweepParameter> parse_sweep_values(const std::string& key, const std::string& text) {
  check_key(key);
  try {
    return parse_values(key, text);
  } catch (const BadValues& e) {
    throw ConfigError("sweep " + key + "=" + text + ": " + e.rule);
  }
}

const char* to_string(SweepMethod method) {
  switch (method) {
    case SweepMethod::grid:
      return "grid";
    case SweepMethod::random:
      return "random";
    case SweepMethod::tpe:
      return "tpe";
    case SweepMethod::cmaes:
      return "cmaes";
    case SweepMethod::nsga2:
      return "nsga2";
    case SweepMethod::qmc:
      return "qmc";
  }
  return "?";
}

std::optional<SweepMethod> parse_sweep_method(const std::string& name) {
  for (const auto m : {SweepMethod::grid, SweepMethod::random, SweepMethod::tpe, SweepMethod::cmaes,
                       SweepMethod::nsga2, SweepMethod::qmc}) {
    if (name == to_string(m)) return m;
  }
  return std::nullopt;
}

bool model_based(SweepMethod method) {
  return method != SweepMethod::grid && method != SweepMethod::random;
}

SweepMethod SweepSpec::resolved_method() const {
  if (method) return *method;
  if (trials > 0) return SweepMethod::random;
  for (const auto& p : parameters) {
    if (!p.enumerable()) return SweepMethod::random;
  }
  return SweepMethod::grid;
}

void SweepSpec::validate() const {
  if (parameters.empty()) {
    throw ConfigError(
        "sweep: no parameters to vary; give key=v1,v2 (or a function such as "
        "log_uniform(1e-4,1e-1)) on the command line or a sweep.parameters block");
  }
  if (repeats < 1) throw ConfigError("sweep: repeats = 0: must be at least 1");
  const SweepMethod m = resolved_method();
  if (!model_based(m)) {
    const std::string what = !sampler.empty()        ? "sampler options need"
                             : !objectives.empty()   ? "objectives need"
                             : pruner.name != "none" ? "pruner " + pruner.name + " needs"
                                                     : "";
    if (!what.empty()) {
      throw ConfigError("sweep: " + what + " a model-based method (tpe, cmaes, nsga2, qmc), not " +
                        to_string(m));
    }
  }
  if (model_based(m)) {
    if (trials < 1) {
      throw ConfigError(std::string("sweep: method ") + to_string(m) +
                        " needs a number of trials (--trials N or sweep.trials)");
    }
    if (report_every < 1) throw ConfigError("sweep: report_every = 0: must be at least 1");
    if (objectives.size() > 1 && pruner.name != "none") {
      throw ConfigError("sweep: pruner " + pruner.name +
                        " with several objectives: Optuna prunes single-objective studies only");
    }
    return;
  }
  if (m == SweepMethod::random) {
    if (trials < 1) {
      throw ConfigError(
          "sweep: random search needs a number of trials (--trials N or sweep.trials)");
    }
    return;
  }
  if (trials > 0) {
    throw ConfigError("sweep: trials = " + std::to_string(trials) +
                      ": a grid runs every combination; trials is for method random");
  }
  for (const auto& p : parameters) {
    if (!p.enumerable()) {
      throw ConfigError("sweep " + p.key + "=" + p.text +
                        ": a grid cannot enumerate a continuous distribution; use method random "
                        "with a number of trials");
    }
  }
}

void SweepSpec::set(SweepParameter parameter) {
  for (auto& p : parameters) {
    if (p.key == parameter.key) {
      p = std::move(parameter);
      return;
    }
  }
  parameters.push_back(std::move(parameter));
}

Objective parse_objective(const std::string& text) {
  Objective o;
  const auto colon = text.find(':');
  o.metric = text.substr(0, colon);
  const std::string mode = colon == std::string::npos ? "min" : text.substr(colon + 1);
  if (o.metric.empty() || (mode != "min" && mode != "max")) {
    throw ConfigError("objective '" + text + "': expected METRIC, METRIC:min or METRIC:max");
  }
  o.maximize = mode == "max";
  return o;
}

SweepArguments split_sweep_arguments(const std::vector<std::string>& words) {
  SweepArguments out;
  for (const auto& word : words) {
    const auto eq = word.find('=');
    if (eq == std::string::npos) {
      throw ConfigError("sweep argument '" + word + "': expected key=value or key=v1,v2,...");
    }
    const std::string key = word.substr(0, eq);
    auto p = parse_sweep_values(key, word.substr(eq + 1));
    if (p) {
      out.parameters.push_back(std::move(*p));
    } else {  // one value: a plain override of each linked key
      for (const auto& k : linked_keys(key)) out.overrides.push_back(k + word.substr(eq));
    }
  }
  return out;
}

SweepSpec read_sweep_block(const std::filesystem::path& file,
                           const std::vector<std::string>& overrides, const std::string& profile) {
  ConfigDocument doc = ConfigDocument::load(file, profile);
  for (const auto& text : overrides) doc.apply(parse_override(text));
  const ConfigReader root = doc.root();
  for (const auto& key : root.keys()) {
    if (key != "sweep") root.raw(key);  // the experiment reader checks those
  }
  SweepSpec spec = read_sweep_section(root.section("sweep"));
  doc.check_all_consumed();
  return spec;
}

SweepSpec read_sweep_section(const ConfigReader& s) {
  SweepSpec spec;
  sweep_fields().read(s, spec);
  s.validate([&] { sweep_fields().check(spec); });
  return spec;
}

SweepParameter parse_sweep_parameter(const std::string& key, const YAML::Node& node) {
  check_key(key);
  std::optional<SweepParameter> p;
  if (node.IsSequence()) {
    if (node.size() == 0) throw ConfigError("empty list of values");
    p.emplace();
    p->key = key;
    p->text = node_text(node);
    for (const auto& v : node) p->values.push_back(YAML::Clone(v));
  } else if (node.IsScalar()) {
    try {
      p = parse_values(key, node.Scalar());
    } catch (const BadValues& e) {
      throw ConfigError(e.rule);
    }
    if (!p) {  // one value: a fixed setting
      p.emplace();
      p->key = key;
      p->text = node.Scalar();
      p->values.push_back(YAML::Clone(node));
    }
  } else {
    throw ConfigError("expected a list of values or a text such as log_uniform(1e-4, 1e-1)");
  }
  return std::move(*p);
}

}  // namespace cnclab
