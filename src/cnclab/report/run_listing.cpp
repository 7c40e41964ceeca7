#include "cnclab/report/run_listing.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <tuple>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/suggest.hpp"
#include "cnclab/experiment/run_warnings.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/report/text_table.hpp"

namespace cnclab {
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kRunFields = {
    "file",      "experiment",   "kind",        "status",         "profile",       "host",
    "start_utc", "wall_seconds", "cpu_seconds", "project_commit", "project_dirty", "config_hash"};

// Table and Markdown show at most this many config keys and metrics by
// default (CSV and JSON all of them); --columns chooses others.
constexpr std::size_t kDefaultConfigColumns = 10;
constexpr std::size_t kDefaultMetricColumns = 8;

std::optional<double> as_number(const std::string& text) {
  double v = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (ec != std::errc() || ptr != end || text.empty()) return std::nullopt;
  return v;
}

std::optional<std::string> field_value(const IndexedRun& r, const std::string& key) {
  const Provenance& p = r.summary.provenance;
  if (key == "file") return r.file.string();
  if (key == "experiment") return r.summary.experiment;
  if (key == "kind") return r.summary.kind;
  if (key == "status") return status_text(p.status, r.summary.warnings);
  if (key == "profile") return p.profile;
  if (key == "host") return p.host;
  if (key == "start_utc") return p.start_utc;
  if (key == "wall_seconds") return shortest_double(p.wall_seconds);
  if (key == "cpu_seconds")
    return p.cpu_seconds < 0 ? std::nullopt : std::optional(shortest_double(p.cpu_seconds));
  if (key == "project_commit") return p.project_commit;
  if (key == "project_dirty") return p.project_dirty;
  if (key == "config_hash") return r.summary.config_hash;
  return std::nullopt;
}

bool is_field(const std::string& key) {
  return std::find(kRunFields.begin(), kRunFields.end(), key) != kRunFields.end();
}

bool holds(const RunCondition& c, const std::string& have) {
  if (c.op == "~") return have.find(c.value) != std::string::npos;
  const auto a = as_number(have), b = as_number(c.value);
  int cmp = 0;
  if (a && b) {
    if (std::isnan(*a) || std::isnan(*b)) return c.op == "!=";
    cmp = *a < *b ? -1 : (*a > *b ? 1 : 0);
  } else {
    cmp = have.compare(c.value);
    cmp = cmp < 0 ? -1 : (cmp > 0 ? 1 : 0);
  }
  if (c.op == "=") return cmp == 0;
  if (c.op == "!=") return cmp != 0;
  if (c.op == "<") return cmp < 0;
  if (c.op == "<=") return cmp <= 0;
  if (c.op == ">") return cmp > 0;
  return cmp >= 0;  // ">="
}

std::string metric_header(const std::string& name, const std::vector<const IndexedRun*>& runs) {
  for (const auto* r : runs) {
    const auto it = r->summary.metric_units.find(name);
    if (it != r->summary.metric_units.end() && !it->second.empty()) {
      return name + " [" + it->second + "]";
    }
  }
  return name;
}

std::string display_file(const fs::path& file) {
  std::error_code ec;
  const fs::path here = fs::current_path(ec);
  if (ec) return file.string();
  const fs::path rel = file.lexically_proximate(here);
  return rel.empty() ? file.string() : rel.string();
}

struct Columns {
  std::vector<std::string> keys;  // resolved
  std::vector<std::string> header;
  std::string note;  // columns left out of the defaults
};

Columns choose_columns(const std::vector<const IndexedRun*>& runs,
                       const std::vector<IndexedRun>& all, const RunsQuery& q) {
  Columns c;
  const bool full = q.format == "csv" || q.format == "json";
  if (!q.columns.empty()) {
    c.keys.push_back("file");
    for (const auto& k : q.columns) {
      const std::string key = resolve_run_key(k, all);
      if (key != "file") c.keys.push_back(key);
    }
  } else {
    c.keys = {"file", "experiment", "status"};
    // Config keys whose text differs among the listed runs (or that some lack).
    std::vector<std::string> order;
    std::set<std::string> seen;
    for (const auto* r : runs) {
      for (const auto& [key, value] : r->config) {
        if (seen.insert(key).second) order.push_back(key);
      }
    }
    std::vector<std::string> varying;
    for (const auto& key : order) {
      if (key == "name") continue;  // the experiment column
      std::optional<std::string> first;
      bool differs = false;
      for (const auto* r : runs) {
        const auto v = run_value(*r, key);
        if (r == runs.front()) {
          first = v;
        } else if (v != first) {
          differs = true;
          break;
        }
      }
      if (differs) varying.push_back(key);
    }
    std::set<std::string> metrics;
    for (const auto* r : runs) {
      for (const auto& [name, value] : r->summary.metrics) metrics.insert(name);
    }
    std::vector<std::string> metric_list(metrics.begin(), metrics.end());
    std::string sort_key =
        q.sort.empty() ? "" : resolve_run_key(q.sort[0] == '-' ? q.sort.substr(1) : q.sort, all);
    const auto limit = [&](std::vector<std::string>& list, std::size_t n, const char* what) {
      if (full || list.size() <= n) return;
      const std::size_t left = list.size() - n;
      const auto sort_at = std::find(list.begin(), list.end(), sort_key);
      const bool keep_sort =
          sort_at != list.end() && sort_at - list.begin() >= static_cast<long>(n);
      list.resize(n);
      if (keep_sort) list.back() = sort_key;
      c.note += (c.note.empty() ? "" : "; ") + std::to_string(left) + " more " + what;
    };
    limit(varying, kDefaultConfigColumns, "config keys vary");
    limit(metric_list, kDefaultMetricColumns, "metrics");
    c.keys.insert(c.keys.end(), varying.begin(), varying.end());
    c.keys.insert(c.keys.end(), metric_list.begin(), metric_list.end());
    if (!c.note.empty()) c.note += " (--columns KEY,... or --format csv|json shows them)";
  }
  for (const auto& key : c.keys) {
    bool metric = false;
    for (const auto* r : runs) metric = metric || r->summary.metrics.count(key) > 0;
    c.header.push_back(metric ? metric_header(key, runs) : key);
  }
  return c;
}

}  // namespace

RunCondition parse_run_condition(const std::string& text) {
  static const std::vector<std::string> ops = {"<=", ">=", "!=", "==", "=", "<", ">", "~"};
  std::size_t at = std::string::npos;
  std::string op;
  for (const auto& o : ops) {
    const auto pos = text.find(o);
    if (pos != std::string::npos && (pos < at || (pos == at && o.size() > op.size()))) {
      at = pos;
      op = o;
    }
  }
  const auto trim = [](std::string s) {
    const auto b = s.find_first_not_of(" \t");
    const auto e = s.find_last_not_of(" \t");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
  };
  if (at == std::string::npos) {
    throw ConfigError("--where '" + text +
                      "': expected KEY OP VALUE with OP one of = != < <= > >= ~");
  }
  RunCondition c{trim(text.substr(0, at)), op == "==" ? "=" : op,
                 trim(text.substr(at + op.size()))};
  if (c.key.empty() || c.value.empty()) {
    throw ConfigError("--where '" + text + "': expected KEY OP VALUE (a key and a value around " +
                      op + ")");
  }
  return c;
}

std::optional<std::string> run_value(const IndexedRun& r, const std::string& key) {
  if (is_field(key)) return field_value(r, key);
  const auto m = r.summary.metrics.find(key);
  if (m != r.summary.metrics.end()) return shortest_double(m->second);
  for (const auto& [k, v] : r.config) {
    if (k == key) return v;
  }
  return std::nullopt;
}

std::string resolve_run_key(const std::string& key, const std::vector<IndexedRun>& runs) {
  if (is_field(key)) return key;
  std::set<std::string> names;
  for (const auto& r : runs) {
    for (const auto& [name, value] : r.summary.metrics) names.insert(name);
    for (const auto& [name, value] : r.config) names.insert(name);
  }
  if (names.count(key)) return key;
  std::vector<std::string> endings;
  for (const auto& n : names) {
    if (n.size() > key.size() && n.compare(n.size() - key.size(), key.size(), key) == 0 &&
        n[n.size() - key.size() - 1] == '.')
      endings.push_back(n);
  }
  if (endings.size() == 1) return endings.front();
  if (endings.size() > 1) {
    std::string list;
    for (const auto& e : endings) list += (list.empty() ? "" : ", ") + e;
    throw ConfigError("key '" + key + "' is ambiguous: " + list);
  }
  std::vector<std::string> all(names.begin(), names.end());
  all.insert(all.end(), kRunFields.begin(), kRunFields.end());
  throw ConfigError("key '" + key + "': no run field, metric or config key of the listed runs" +
                    did_you_mean(key, all));
}

std::vector<const IndexedRun*> select_runs(const std::vector<IndexedRun>& runs,
                                           const RunsQuery& q) {
  std::vector<RunCondition> conditions = q.where;
  for (auto& c : conditions) c.key = resolve_run_key(c.key, runs);
  std::vector<const IndexedRun*> out;
  for (const auto& r : runs) {
    const bool ok = std::all_of(conditions.begin(), conditions.end(), [&](const RunCondition& c) {
      const auto v = run_value(r, c.key);
      return v && holds(c, *v);
    });
    if (ok) out.push_back(&r);
  }
  if (q.sort.empty()) return out;
  const bool descending = q.sort[0] == '-';
  const std::string key = resolve_run_key(descending ? q.sort.substr(1) : q.sort, runs);
  // Runs without the key (or NaN) last in either order; numbers as numbers.
  const auto rank = [&](const IndexedRun* r) {
    const auto v = run_value(*r, key);
    const auto n = v ? as_number(*v) : std::nullopt;
    return std::tuple(!v || (n && std::isnan(*n)), n, v);
  };
  std::stable_sort(out.begin(), out.end(), [&](const IndexedRun* a, const IndexedRun* b) {
    const auto [missing_a, na, ta] = rank(a);
    const auto [missing_b, nb, tb] = rank(b);
    if (missing_a != missing_b) return missing_b;
    if (missing_a) return false;
    if (na && nb) return descending ? *na > *nb : *na < *nb;
    return descending ? *ta > *tb : *ta < *tb;
  });
  return out;
}

void print_runs(const std::vector<const IndexedRun*>& runs, const std::vector<IndexedRun>& all,
                const RunsQuery& q, std::ostream& out) {
  const Columns c = choose_columns(runs, all, q);
  if (q.format == "json") {
    using Json = nlohmann::ordered_json;
    Json rows = Json::array();
    for (const auto* r : runs) {
      Json row = {{"file", r->file.string()},
                  {"experiment", r->summary.experiment},
                  {"kind", r->summary.kind},
                  {"status", r->summary.provenance.status},
                  {"warnings", r->summary.warnings}};
      Json config = Json::object(), metrics = Json::object();
      for (const auto& key : c.keys) {
        if (is_field(key) || r->summary.metrics.count(key)) continue;
        const auto v = run_value(*r, key);
        config[key] = v ? Json(*v) : Json(nullptr);
      }
      for (const auto& [name, value] : r->summary.metrics) {
        metrics[name] = std::isfinite(value) ? Json(value) : Json(nullptr);
      }
      row["config"] = std::move(config);
      row["metrics"] = std::move(metrics);
      row["units"] = r->summary.metric_units;
      rows.push_back(std::move(row));
    }
    out << Json{{"runs", std::move(rows)}}.dump(1) << "\n";
    return;
  }
  TextTable t;
  t.header = c.header;
  for (const auto* r : runs) {
    std::vector<std::string> row;
    for (const auto& key : c.keys) {
      if (key == "file") {
        row.push_back(q.format == "csv" ? r->file.string() : display_file(r->file));
        continue;
      }
      const auto m = r->summary.metrics.find(key);
      if (m != r->summary.metrics.end()) {
        row.push_back(q.format == "csv" ? shortest_double(m->second) : format_metric(m->second));
        continue;
      }
      const auto v = run_value(*r, key);
      row.push_back(v ? *v : (q.format == "csv" ? "" : kMissingCell));
    }
    t.rows.push_back(std::move(row));
  }
  if (q.format == "csv") {
    t.print_csv(out);
    return;
  }
  if (q.format == "md") {
    t.print_markdown(out);
  } else {
    t.print_aligned(out);
  }
  out << "\n" << runs.size() << " of " << all.size() << " runs";
  if (!c.note.empty()) out << "; " << c.note;
  out << "\n";
}

}  // namespace cnclab
