#include "cnclab/report/targets.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "cnclab/core/config.hpp"
#include "cnclab/core/suggest.hpp"
#include "cnclab/experiment/result_store.hpp"
#include "cnclab/report/text_table.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

constexpr const char* kOpsText = ">=, <=, ==, < or >";

std::optional<TargetOp> parse_op(const std::string& text) {
  for (TargetOp op : {TargetOp::ge, TargetOp::le, TargetOp::eq, TargetOp::lt, TargetOp::gt}) {
    if (text == to_string(op)) return op;
  }
  return std::nullopt;
}

// `where`: "<file>:<line>:<col>: targets[i]" (the document indexes list
// entries without their position, so it comes from the entry's YAML mark).
Target read_target(const ConfigReader& r, std::string where) {
  static const std::vector<std::string> kKeys = {"name", "op", "value", "profiles", "source"};
  for (const auto& k : r.keys()) {
    if (std::find(kKeys.begin(), kKeys.end(), k) == kKeys.end()) {
      r.fail(k, "unknown key" + did_you_mean(k, kKeys) + "; allowed: name, op, value, profiles, " +
                    "source");
    }
  }
  Target t;
  t.where = std::move(where);
  t.name = r.require<std::string>("name");
  r.check(!t.name.empty(), "name", "must name a measured quantity");
  const auto op = parse_op(r.require<std::string>("op"));
  if (!op) r.fail("op", std::string("must be one of ") + kOpsText + " (quoted in YAML: \">=\")");
  t.op = *op;
  t.value = r.require<double>("value");
  const ConfigReader profiles = r.section("profiles");
  for (const auto& p : profiles.keys()) {
    profiles.check(!p.empty(), p, "profile names are not empty");
    t.profiles[p] = profiles.require<double>(p);
  }
  t.source = r.require<std::string>("source");
  r.check(!t.source.empty(), "source",
          "must say where the target comes from (a paper, a section, or a measurement in docs/)");
  return t;
}

// A long value as the tables print it: 4 significant digits would hide a
// 99.49 against a 99.5 target, so 6.
std::string number(double v) {
  return table_number(v, 6);
}

// Names of `measured` sharing the longest dotted prefix with `name` (at most
// kShown of them), for an unknown name's message.
std::string nearby_names(const std::string& name, const Measurements& measured) {
  constexpr std::size_t kShown = 24;
  std::string prefix = name;
  while (!prefix.empty()) {
    const auto dot = prefix.rfind('.');
    prefix = dot == std::string::npos ? std::string() : prefix.substr(0, dot + 1);
    std::vector<std::string> hits;
    for (const auto& [k, v] : measured) {
      if (k.rfind(prefix, 0) == 0) hits.push_back(k);
    }
    if (!hits.empty() && (!prefix.empty() || hits.size() <= kShown)) {
      std::string text;
      for (std::size_t i = 0; i < hits.size() && i < kShown; ++i) {
        text += (i ? ", " : "") + hits[i];
      }
      if (hits.size() > kShown) text += ", ... (" + std::to_string(hits.size()) + " in all)";
      return (prefix.empty() ? "known: " : "known under '" + prefix + "': ") + text;
    }
    if (!prefix.empty()) prefix.pop_back();  // drop the dot, look one level up
  }
  std::set<std::string> groups;
  for (const auto& [k, v] : measured) groups.insert(k.substr(0, k.find('.')));
  std::string text;
  for (const auto& g : groups) text += (text.empty() ? "" : ", ") + g + ".*";
  return "known groups: " + text;
}

}  // namespace

const char* to_string(TargetOp op) {
  switch (op) {
    case TargetOp::ge:
      return ">=";
    case TargetOp::le:
      return "<=";
    case TargetOp::eq:
      return "==";
    case TargetOp::lt:
      return "<";
    case TargetOp::gt:
      return ">";
  }
  return "?";
}

bool holds(TargetOp op, double measured, double wanted) {
  if (std::isnan(measured) || std::isnan(wanted)) return false;
  switch (op) {
    case TargetOp::ge:
      return measured >= wanted;
    case TargetOp::le:
      return measured <= wanted;
    case TargetOp::eq:
      return measured == wanted;  // exact: counts (targets.hpp)
    case TargetOp::lt:
      return measured < wanted;
    case TargetOp::gt:
      return measured > wanted;
  }
  return false;
}

std::optional<double> Target::value_for(const std::string& profile) const {
  if (profile.empty()) return value;
  const auto it = profiles.find(profile);
  if (it == profiles.end()) return std::nullopt;
  return it->second;
}

std::vector<Target> read_targets(const fs::path& manifest) {
  if (!fs::exists(manifest)) throw MissingResults(manifest.string() + ": study manifest not found");
  const ConfigDocument doc = ConfigDocument::load(manifest);
  const ConfigReader root = doc.root();
  std::vector<Target> targets;
  if (!root.has("targets")) return targets;
  const YAML::Node list = root.raw("targets");
  if (!list.IsSequence()) {
    root.fail("targets", "must be a list of {name, op, value, source} entries");
  }
  // Entry positions: the resolved tree is rebuilt from the file and its
  // includes without marks, so they come from the file read once more; a
  // list from an include falls back to the position of `targets:`.
  YAML::Node own;
  try {
    own = YAML::LoadFile(manifest.string())["targets"];
  } catch (const YAML::Exception&) {
  }
  const bool marked = own && own.IsSequence() && own.size() == list.size();
  for (std::size_t i = 0; i < list.size(); ++i) {
    SourceLocation at = root.location("targets");
    if (marked) at = {manifest.string(), own[i].Mark().line + 1, own[i].Mark().column + 1};
    targets.push_back(
        read_target(root.element("targets", i), at.str() + ": targets[" + std::to_string(i) + "]"));
  }
  return targets;
}

std::vector<TargetResult> check_targets(const std::vector<Target>& targets,
                                        const Measurements& measured, const std::string& profile) {
  std::vector<std::string> names;
  for (const auto& [k, v] : measured) names.push_back(k);
  std::vector<TargetResult> results;
  for (const auto& t : targets) {
    const auto it = measured.find(t.name);
    if (it == measured.end()) {
      throw ConfigError(t.where + ".name = " + t.name + ": not a quantity this table measures" +
                        did_you_mean(t.name, names) + "; " + nearby_names(t.name, measured));
    }
    TargetResult r;
    r.target = &t;
    r.measured = it->second;
    r.wanted = t.value_for(profile);
    r.pass = r.wanted && holds(t.op, r.measured, *r.wanted);
    results.push_back(r);
  }
  return results;
}

void print_target_results(std::ostream& out, TableFormat format, const std::string& table,
                          const fs::path& manifest, const std::string& profile,
                          const std::vector<TargetResult>& results) {
  TextTable t;
  t.header = {"quantity", "target", "measured", "result", "source"};
  for (const auto& r : results) {
    const Target& g = *r.target;
    std::string bound = to_string(g.op);
    bound += " ";
    bound += number(r.wanted ? *r.wanted : g.value);
    if (!r.wanted) {
      // The full study's bound, in brackets: not checked here. Appended, not
      // `"(" + std::string`: GCC 12 warns falsely (-Wrestrict, PR105329).
      std::string shown = "(";
      shown += bound;
      shown += ")";
      t.rows.push_back({g.name, shown, number(r.measured), "not checked", g.source});
      continue;
    }
    t.rows.push_back({g.name, bound, number(r.measured), r.pass ? "PASS" : "FAIL", g.source});
  }
  print_table_title(out, format,
                    "Targets of `cnclab tables " + table + "` (" + source_path_text(manifest) +
                        ", " + (profile.empty() ? "full study" : "profile " + profile) + ")");
  t.print(out, format);
  std::size_t failed = 0, unchecked = 0;
  for (const auto& r : results) {
    failed += r.wanted && !r.pass ? 1 : 0;
    unchecked += r.wanted ? 0 : 1;
  }
  std::vector<std::string> notes = {std::to_string(results.size() - failed - unchecked) +
                                    " PASS, " + std::to_string(failed) + " FAIL"};
  if (unchecked > 0) {
    notes.push_back(std::to_string(unchecked) + " not checked: declared for the full study" +
                    " only (targets.hpp: a profile's results are checked against the targets " +
                    "that give a value for it under `profiles:`)");
  }
  print_table_notes(out, format, notes);
}

TableCheck check_table(const TableEntry& table, const LoadedTables& loaded,
                       const TablesOptions& options, std::ostream& out) {
  TableCheck c;
  if (table.manifest.empty() || !table.measure) {
    print_table_notes(out, options.format, {"table " + table.name + ": no targets declared"});
    return c;
  }
  const fs::path manifest = options.config_file(table.manifest);
  const std::vector<Target> targets = read_targets(manifest);
  if (targets.empty()) {
    print_table_notes(
        out, options.format,
        {"table " + table.name + ": no targets declared in " + source_path_text(manifest)});
    return c;
  }
  c.declared = true;
  const Measurements measured = loaded.measure();
  const std::vector<TargetResult> results = check_targets(targets, measured, options.profile);
  print_target_results(out, options.format, table.name, manifest, options.profile, results);
  for (const auto& r : results) {
    if (!r.wanted) {
      ++c.unchecked;
    } else if (r.pass) {
      ++c.passed;
    } else {
      ++c.failed;
    }
  }
  return c;
}

}  // namespace cnclab
