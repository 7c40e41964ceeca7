#include "cnclab/report/compare.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>

#include "cnclab/core/config.hpp"
#include "cnclab/core/config_abbreviate.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/run_warnings.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/report/text_table.hpp"
#include "cnclab/sweep/sweep_plan.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

struct Comparison {
  std::vector<std::string> labels;  // [1], [2], ...
  std::vector<std::pair<std::string, std::vector<std::optional<std::string>>>> config;
  std::vector<std::pair<std::string, std::vector<std::optional<double>>>> metrics;
  std::map<std::string, std::string> units;  // per metric: the first run's that names one
};

Comparison build(const std::vector<ComparedRun>& runs, bool full) {
  Comparison c;
  std::vector<std::map<std::string, std::string>> flat;
  std::vector<std::string> keys;
  std::set<std::string> seen;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    // Appended, not `"[" + std::string`: GCC 12 warns falsely (-Wrestrict, PR105329).
    std::string label = "[";
    label += std::to_string(i + 1);
    label += "]";
    c.labels.push_back(std::move(label));
    flat.emplace_back();
    for (auto& [k, v] : flatten_config(runs[i].record.resolved_yaml, full)) {
      if (seen.insert(k).second) keys.push_back(k);
      flat.back()[k] = v;
    }
  }
  for (const auto& k : keys) {
    std::vector<std::optional<std::string>> values;
    for (const auto& f : flat) {
      const auto it = f.find(k);
      values.push_back(it == f.end() ? std::nullopt : std::optional<std::string>(it->second));
    }
    if (std::adjacent_find(values.begin(), values.end(), std::not_equal_to<>()) != values.end()) {
      c.config.emplace_back(k, std::move(values));
    }
  }
  std::set<std::string> names;
  for (const auto& r : runs) {
    for (const auto& [name, value] : r.record.metrics) names.insert(name);
    for (const auto& [name, unit] : r.record.metric_units) {
      if (!unit.empty()) c.units.emplace(name, unit);
    }
  }
  for (const auto& name : names) {
    std::vector<std::optional<double>> values;
    for (const auto& r : runs) {
      const auto it = r.record.metrics.find(name);
      values.push_back(it == r.record.metrics.end() ? std::nullopt
                                                    : std::optional<double>(it->second));
    }
    c.metrics.emplace_back(name, std::move(values));
  }
  return c;
}

std::optional<double> delta(const std::vector<std::optional<double>>& v, std::size_t i) {
  if (i == 0 || !v[0] || !v[i]) return std::nullopt;
  return *v[i] - *v[0];
}

std::string delta_text(const std::vector<std::optional<double>>& v, std::size_t i) {
  const auto d = delta(v, i);
  if (!d) return "";
  std::string s = *d >= 0 ? "+" : "";
  s += format_metric(*d);
  if (*v[0] != 0) {
    const double pct = 100.0 * *d / std::abs(*v[0]);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%+.1f%%", pct);
    s += ", " + std::string(buf);
  }
  return s;
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  return out + "\"";
}

std::string json_number(const std::optional<double>& v) {
  return v && std::isfinite(*v) ? shortest_double(*v) : "null";
}

void print_json(const std::vector<ComparedRun>& runs, const Comparison& c, std::ostream& out) {
  out << "{\n  \"runs\": [\n";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const RunRecord& r = runs[i].record;
    out << "    {\"label\": " << json_string(c.labels[i])
        << ", \"file\": " << json_string(runs[i].file.string())
        << ", \"experiment\": " << json_string(r.experiment)
        << ", \"status\": " << json_string(r.provenance.status)
        << ", \"warnings\": " << json_string(join_warnings(r.warnings))
        << ", \"config_hash\": " << json_string(r.config_hash) << "}"
        << (i + 1 < runs.size() ? "," : "") << "\n";
  }
  out << "  ],\n  \"config\": {";
  for (std::size_t k = 0; k < c.config.size(); ++k) {
    out << (k ? "," : "") << "\n    " << json_string(c.config[k].first) << ": [";
    const auto& v = c.config[k].second;
    for (std::size_t i = 0; i < v.size(); ++i) {
      out << (i ? ", " : "") << (v[i] ? json_string(*v[i]) : "null");
    }
    out << "]";
  }
  out << (c.config.empty() ? "" : "\n  ") << "},\n  \"metrics\": {";
  for (std::size_t m = 0; m < c.metrics.size(); ++m) {
    const auto& v = c.metrics[m].second;
    const auto unit = c.units.find(c.metrics[m].first);
    out << (m ? "," : "") << "\n    " << json_string(c.metrics[m].first)
        << ": {\"unit\": " << json_string(unit == c.units.end() ? "" : unit->second)
        << ", \"values\": [";
    for (std::size_t i = 0; i < v.size(); ++i) out << (i ? ", " : "") << json_number(v[i]);
    out << "], \"delta_to_first\": [";
    for (std::size_t i = 0; i < v.size(); ++i) out << (i ? ", " : "") << json_number(delta(v, i));
    out << "]}";
  }
  out << (c.metrics.empty() ? "" : "\n  ") << "}\n}\n";
}

TextTable csv_table(const Comparison& c) {
  TextTable t;
  t.header = {"kind", "key"};
  for (const auto& l : c.labels) t.header.push_back(l);
  for (std::size_t i = 1; i < c.labels.size(); ++i) {
    t.header.push_back("delta " + c.labels[i] + "-" + c.labels[0]);
  }
  for (const auto& [key, v] : c.config) {
    std::vector<std::string> row = {"config", key};
    for (const auto& x : v) row.push_back(x ? *x : "");
    row.resize(t.header.size());
    t.rows.push_back(std::move(row));
  }
  for (const auto& [name, v] : c.metrics) {
    std::vector<std::string> row = {"metric", name};
    for (const auto& x : v) row.push_back(x ? shortest_double(*x) : "");
    for (std::size_t i = 1; i < v.size(); ++i) {
      const auto d = delta(v, i);
      row.push_back(d ? shortest_double(*d) : "");
    }
    t.rows.push_back(std::move(row));
  }
  return t;
}

TextTable display_table(const std::vector<ComparedRun>& runs, const Comparison& c) {
  TextTable t;
  t.header = {""};
  for (const auto& l : c.labels) t.header.push_back(l);
  std::vector<std::string> status = {"status"};
  for (const auto& r : runs)
    status.push_back(status_text(r.record.provenance.status, r.record.warnings));
  t.rows.push_back(std::move(status));
  for (const auto& [key, v] : c.config) {
    std::vector<std::string> row = {key};
    for (const auto& x : v) row.push_back(x ? *x : kMissingCell);
    t.rows.push_back(std::move(row));
  }
  for (const auto& [name, v] : c.metrics) {
    const auto unit = c.units.find(name);
    std::vector<std::string> row = {unit == c.units.end() ? name
                                                          : name + " [" + unit->second + "]"};
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!v[i]) {
        row.push_back(kMissingCell);
        continue;
      }
      const std::string d = delta_text(v, i);
      row.push_back(format_metric(*v[i]) + (d.empty() ? "" : " (" + d + ")"));
    }
    t.rows.push_back(std::move(row));
  }
  return t;
}

void flatten(const YAML::Node& node, const std::string& prefix,
             std::vector<std::pair<std::string, std::string>>& out) {
  if (node.IsMap()) {
    for (auto it = node.begin(); it != node.end(); ++it) {
      const YAML::Node key = it->first;
      const YAML::Node value = it->second;
      flatten(value, prefix.empty() ? key.Scalar() : prefix + "." + key.Scalar(), out);
    }
    return;
  }
  // A list of maps (trainer.stages) by entry: trainer.stages[1].epochs.
  const bool maps =
      node.IsSequence() && node.size() > 0 &&
      std::all_of(node.begin(), node.end(), [](const YAML::Node& n) { return n.IsMap(); });
  if (maps) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      flatten(node[i], prefix + "[" + std::to_string(i) + "]", out);
    }
    return;
  }
  out.emplace_back(prefix, node_text(node));
}

}  // namespace

CompareFormat parse_compare_format(const std::string& text) {
  if (text == "table") return CompareFormat::table;
  if (text == "md" || text == "markdown") return CompareFormat::markdown;
  if (text == "csv") return CompareFormat::csv;
  if (text == "json") return CompareFormat::json;
  throw ConfigError("--format " + text + ": must be one of: table, md, csv, json");
}

std::vector<std::pair<std::string, std::string>> flatten_config(const std::string& yaml_text,
                                                                bool full) {
  std::vector<std::pair<std::string, std::string>> out;
  try {
    flatten(YAML::Load(full ? yaml_text : abbreviate_config(yaml_text).text), "", out);
  } catch (const YAML::Exception& e) {
    throw IoError("stored config is not valid YAML: " + e.msg);
  }
  return out;
}

std::vector<ComparedRun> collect_runs(const std::vector<std::string>& inputs) {
  std::vector<ComparedRun> runs;
  for (const auto& input : inputs) {
    std::error_code ec;
    std::vector<fs::path> files;
    if (fs::is_regular_file(input, ec)) {
      files.emplace_back(input);
    } else if (fs::is_directory(input, ec) && fs::exists(fs::path(input) / "sweep.yaml", ec)) {
      // A sweep folder: its trials with a result, in plan order.
      for (const auto& t : load_plan(input).trials) {
        const fs::path f = trial_result_path(input, t.id);
        if (fs::exists(f, ec)) files.push_back(f);
      }
      if (files.empty()) throw ConfigError(input + ": no trial of this sweep has a result yet");
    } else if (fs::is_directory(input, ec)) {
      for (const auto& e : fs::recursive_directory_iterator(input)) {
        const fs::path& p = e.path();
        if (e.is_regular_file() && p.extension() == ".h5" && !is_partial_path(p) &&
            p.filename() != "summary.h5") {
          files.push_back(p);
        }
      }
      std::sort(files.begin(), files.end());
      if (files.empty()) throw ConfigError(input + ": no result files in this folder");
    } else {
      throw ConfigError(input + ": no such result file or folder");
    }
    for (const auto& f : files) runs.push_back({f, read_result(f)});
  }
  if (runs.size() < 2) {
    throw ConfigError("compare: needs at least two runs (got " + std::to_string(runs.size()) + ")");
  }
  return runs;
}

void print_comparison(const std::vector<ComparedRun>& runs, CompareFormat format, std::ostream& out,
                      bool full) {
  const Comparison c = build(runs, full);
  switch (format) {
    case CompareFormat::json:
      print_json(runs, c, out);
      return;
    case CompareFormat::csv:
      csv_table(c).print_csv(out);
      return;
    case CompareFormat::markdown:
    case CompareFormat::table:
      break;
  }
  const bool md = format == CompareFormat::markdown;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    out << (md ? "- " : "") << (md ? "**" + c.labels[i] + "**" : c.labels[i]) << " "
        << runs[i].file.string() << " (" << runs[i].record.experiment << ")\n";
  }
  out << "\n";
  if (c.config.empty()) out << "(identical configs)\n\n";
  const TextTable t = display_table(runs, c);
  if (md) {
    t.print_markdown(out);
  } else {
    t.print_aligned(out);
  }
  out << "\nonly config keys that differ are shown; metric deltas are to " << c.labels[0];
  if (!full) {
    out << "; arrays of more than " << kAbbreviateScalars
        << " numbers as shape and hash (--full prints them)";
  }
  out << "\n";
}

int compare_command(const std::vector<std::string>& inputs, const std::string& format, bool full,
                    std::ostream& out) {
  const CompareFormat f = parse_compare_format(format);
  print_comparison(collect_runs(inputs), f, out, full);
  return 0;
}

}  // namespace cnclab
