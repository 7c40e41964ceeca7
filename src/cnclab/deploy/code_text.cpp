#include "cnclab/deploy/code_text.hpp"

#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/deploy/deployed_model.hpp"

namespace cnclab {
namespace {

constexpr std::array<const char*, 37> kC99Keywords = {
    "auto",     "break",  "case",   "char",     "const",     "continue", "default",  "do",
    "double",   "else",   "enum",   "extern",   "float",     "for",      "goto",     "if",
    "inline",   "int",    "long",   "register", "restrict",  "return",   "short",    "signed",
    "sizeof",   "static", "struct", "switch",   "typedef",   "union",    "unsigned", "void",
    "volatile", "while",  "_Bool",  "_Complex", "_Imaginary"};

// "name [unit]" items joined, wrapped into lines of about `width` characters.
std::vector<std::string> wrapped(std::string head, const std::vector<std::string>& items,
                                 std::size_t width = 88) {
  head.resize(11, ' ');  // the width of the other lines' heads, less the space before an item
  std::vector<std::string> lines;
  std::string line = head;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::string item = items[i] + (i + 1 < items.size() ? "," : "");
    if (line.size() + 1 + item.size() > width && line.size() > head.size()) {
      lines.push_back(line);
      line = std::string(head.size(), ' ');
    }
    line += " " + item;
  }
  lines.push_back(line);
  return lines;
}

std::vector<std::string> with_units(const std::vector<std::string>& names,
                                    const std::vector<std::string>& units) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < names.size(); ++i) out.push_back(names[i] + " [" + units[i] + "]");
  return out;
}

std::vector<std::string> physical_items(const std::vector<ColumnScaling>& columns,
                                        const std::vector<std::string>& dataset_names) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < columns.size(); ++i) {
    const ColumnScaling& c = columns[i];
    out.push_back(c.name + " [" + c.unit + "] (" + dataset_names[i] + " = mapminmax of [" +
                  shortest_double(c.min) + ", " + shortest_double(c.max) + "])");
  }
  return out;
}

std::string scaling_text(const ScalingRecord& s) {
  if (s.method != Scaling::minmax) return to_string(s.method);
  return "minmax to [" + shortest_double(s.y_min) + ", " + shortest_double(s.y_max) + "]";
}

}  // namespace

std::string to_string(CPrecision precision) {
  return precision == CPrecision::float32 ? "float" : "double";
}

CPrecision parse_precision(const std::string& text) {
  if (text == "float") return CPrecision::float32;
  if (text == "double") return CPrecision::float64;
  throw ConfigError("--precision " + text + ": must be float or double");
}

std::string hex_double(double x) {
  char text[64];
  std::snprintf(text, sizeof text, "%a", x);
  return text;
}

std::string hex_float(float f) {
  return hex_double(static_cast<double>(f)) + "f";
}

std::string CCodeContext::literal(double x) const {
  const bool f = precision == CPrecision::float32;
  const double value = f ? static_cast<double>(static_cast<float>(x)) : x;
  // Short decimals (2.0, 0.5, 1000.0) read better and are as exact: their
  // text reads back to this very value (in float: a value float holds, so
  // the compiler's one rounding of the text cannot differ).
  std::string text = shortest_double(value);
  if (text.size() <= 8 && text.find_first_of("en") == std::string::npos) {
    if (text.find('.') == std::string::npos) text += ".0";
    return f ? text + "f" : text;
  }
  return f ? hex_float(static_cast<float>(x)) : hex_double(x);
}

std::string CCodeContext::math(const std::string& function) const {
  return precision == CPrecision::float32 ? function + "f" : function;
}

std::string export_identifier(const std::string& experiment_name) {
  std::string id;
  for (const char ch : experiment_name) {
    const auto c = static_cast<unsigned char>(std::tolower(static_cast<unsigned char>(ch)));
    id += (std::isalnum(c) != 0 && c < 128) || c == '_' ? static_cast<char>(c) : '_';
  }
  if (id.empty() || std::isdigit(static_cast<unsigned char>(id[0])) != 0) id = "n_" + id;
  return id;
}

void check_export_identifier(const std::string& name) {
  const auto bad = [&](const std::string& rule) {
    throw ConfigError("--name " + name + ": " + rule);
  };
  if (name.empty() || name.size() > 40) bad("must have 1 to 40 characters");
  if (std::isdigit(static_cast<unsigned char>(name[0])) != 0) bad("must not start with a digit");
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (!(u < 128 && (std::isalnum(u) != 0 || c == '_'))) {
      bad("must be a C identifier (letters, digits, '_')");
    }
  }
  for (const char* k : kC99Keywords) {
    if (name == k) bad("is a C keyword");
  }
}

std::vector<std::string> model_description(const DeployedModel& m) {
  std::vector<std::string> lines = {
      "result      " + m.result_file,
      "experiment  " + m.experiment + " (config hash " + m.config_hash + ", result identity " +
          m.identity + ")",
      "trained     " + m.trained_utc + " by cnclab " + m.cnclab_version + " (git " + m.git_commit +
          ")",
      "dataset     generator " + m.generator + ", content hash " + m.dataset_hash,
      "network     " + m.architecture() + ", " + std::to_string(m.num_parameters()) +
          " parameters"};
  const auto add = [&](const std::vector<std::string>& more) {
    lines.insert(lines.end(), more.begin(), more.end());
  };
  if (m.kind == ModelKind::mlp) {
    lines.push_back("scaling     inputs " + scaling_text(m.input_scaling) + ", targets " +
                    scaling_text(m.target_scaling) + " (fitted on the training split; inside)");
  }
  if (m.has_physical_columns()) {
    add(wrapped("in", physical_items(m.physical_inputs, m.input_names)));
    add(wrapped("out", physical_items(m.physical_targets, m.target_names)));
  } else {
    add(wrapped("in", with_units(m.input_names, m.input_units)));
    add(wrapped("out", with_units(m.target_names, m.target_units)));
  }
  lines.push_back(m.metrics.empty() ? "metrics     (none stored)"
                                    : "metrics     (as stored in the result)");
  for (const auto& [name, value] : m.metrics) {
    const auto unit = m.metric_units.find(name);
    const bool unitless =
        unit == m.metric_units.end() || unit->second.empty() || unit->second == "1";
    lines.push_back("  " + name + " = " + shortest_double(value) +
                    (unitless ? "" : " " + unit->second));
  }
  return lines;
}

}  // namespace cnclab
