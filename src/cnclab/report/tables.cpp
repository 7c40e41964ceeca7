#include "cnclab/report/tables.hpp"

#include <algorithm>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "cnclab/core/share_paths.hpp"
#include "cnclab/experiment/profiles.hpp"
#include "cnclab/report/targets.hpp"

namespace cnclab {

double normalised_test_mse(const RunRecord& r) {
  return normalised_test_mse(r, r.test_predictions);
}

double normalised_test_mse(const RunRecord& r, const Eigen::MatrixXd& predictions) {
  const ScalingRecord& y = r.target_scaling;
  return (y.transform(predictions) - y.transform(r.test_targets)).array().square().mean();
}

namespace {

// NAME under `dir` when given, else FOLDER/NAME from the project or cnclab's share.
std::filesystem::path tables_input(const std::filesystem::path& dir, const char* folder,
                                   const std::filesystem::path& name) {
  if (!dir.empty()) return dir / name;
  const std::filesystem::path relative = std::filesystem::path(folder) / name;
  const ShareLookup lookup = find_shared(relative);
  if (!lookup.found) throw MissingResults(lookup.not_found_message(relative));
  return *lookup.found;
}

}  // namespace

std::filesystem::path TablesOptions::experiment_file(const std::filesystem::path& name) const {
  return tables_input(experiments_dir, "experiments", name);
}

std::filesystem::path TablesOptions::reference_file(const std::filesystem::path& name) const {
  return tables_input(reference_dir, "results/reference", name);
}

std::filesystem::path TablesOptions::config_file(const std::filesystem::path& name) const {
  return tables_input(configs_dir, "configs", name);
}

ResultStore table_store(const TablesOptions& options) {
  return ResultStore(options.results_dir, options.profile);
}

void print_table_sources(std::ostream& out, TableFormat format,
                         const std::vector<std::filesystem::path>& files) {
  std::vector<std::string> seen;
  std::string line = "sources:";
  for (const auto& f : files) {
    const std::string text = source_path_text(f);
    if (std::find(seen.begin(), seen.end(), text) != seen.end()) continue;
    line += (seen.empty() ? " " : ", ") + text;
    seen.push_back(text);
  }
  if (format == TableFormat::text) {
    out << "\n" << line << "\n";  // a footer line, not one of the notes
  } else if (format == TableFormat::json) {
    out << nlohmann::json{{"sources", seen}}.dump() << "\n";
  } else {
    print_table_notes(out, format, {line});
  }
}

namespace {

using TablesJson = nlohmann::ordered_json;

// The record lines of a json printout (text_table.hpp) as one document.
TablesJson tables_json_document(const std::string& records) {
  TablesJson tables = TablesJson::array(), notes = TablesJson::array();
  std::string title;
  std::size_t open_from = 0;  // tables that the next notes/sources belong to
  std::istringstream lines(records);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    TablesJson r = TablesJson::parse(line, nullptr, false);
    if (r.is_discarded() || !r.is_object()) {
      notes.push_back(line);  // printed as text ("(Seed 000 Table 8 not printed: ...)")
    } else if (r.contains("title")) {
      title = r["title"].get<std::string>();
    } else if (r.contains("table")) {
      if (open_from < tables.size() &&
          (tables.back().contains("notes") || tables.back().contains("sources"))) {
        open_from = tables.size();
      }
      TablesJson t = {{"title", title}};
      for (auto& [k, v] : r["table"].items()) t[k] = v;
      tables.push_back(std::move(t));
      title.clear();
    } else {
      const std::string key = r.contains("notes") ? "notes" : "sources";
      if (open_from >= tables.size()) {
        for (auto& v : r[key]) notes.push_back(v);
        continue;
      }
      for (std::size_t i = open_from; i < tables.size(); ++i) {
        if (!tables[i].contains(key)) tables[i][key] = TablesJson::array();
        for (auto& v : r[key]) tables[i][key].push_back(v);
      }
    }
  }
  return {{"tables", tables}, {"notes", notes}};
}

std::vector<TableEntry>& table_registry() {
  static std::vector<TableEntry> tables;
  return tables;
}

}  // namespace

void register_table(TableEntry entry) {
  for (const auto& t : table_registry()) {
    if (t.name == entry.name) throw std::logic_error("table '" + entry.name + "' registered twice");
  }
  table_registry().push_back(std::move(entry));
}

const std::vector<TableEntry>& registered_tables() {
  return table_registry();
}

namespace {

// `body` printed to `out`; for json its record lines as one document.
void print_tables_body(const std::string& name, const TablesOptions& options,
                       const std::function<void(std::ostream&)>& body, std::ostream& out) {
  if (options.format != TableFormat::json) return body(out);
  std::ostringstream records;
  body(records);
  const TablesJson doc = tables_json_document(records.str());
  const TablesJson wrapped = {{"name", name},
                              {"profile", options.profile},
                              {"tables", doc["tables"]},
                              {"notes", doc["notes"]}};
  out << wrapped.dump(2) << "\n";
}

}  // namespace

LoadedTables load_tables(const TableEntry& entry, const TablesOptions& options) {
  if (entry.load) return entry.load(options);
  LoadedTables loaded;
  loaded.print = [&entry, options](std::ostream& out) { entry.print(options, out); };
  if (entry.measure) loaded.measure = [&entry, options] { return entry.measure(options); };
  return loaded;
}

void print_table_document(const TableEntry& entry, const TablesOptions& options,
                          std::ostream& out) {
  print_tables_body(
      entry.name, options, [&](std::ostream& o) { entry.print(options, o); }, out);
}

namespace {

// The profile check of `tables NAME --profile P` (the set rule of profiles.hpp).
void check_table_profile(const TableEntry& t, const TablesOptions& options) {
  if (options.profile.empty() || !t.experiment_files) return;
  check_profile_in_set(t.experiment_files(options), options.profile,
                       "the experiment files of table " + t.name);
}

// Whether table `t` reads a result of one of `ran` (weakly canonical); a
// table that does not list its files counts as related.
bool table_related(const TableEntry& t, const TablesOptions& options,
                   const std::vector<std::filesystem::path>& ran) {
  if (!t.experiment_files) return true;
  for (const auto& f : t.experiment_files(options)) {
    if (std::find(ran.begin(), ran.end(), std::filesystem::weakly_canonical(f)) != ran.end()) {
      return true;
    }
  }
  return false;
}

}  // namespace

int tables_command(const std::string& name, const TablesOptions& options, std::ostream& out) {
  const auto& tables = registered_tables();
  std::string known;
  for (const auto& t : tables) {
    if (t.name == name) {
      check_table_profile(t, options);
      // --check's table joins the document (json: one more table).
      int code = 0;
      print_tables_body(
          t.name, options,
          [&](std::ostream& o) {
            const LoadedTables loaded = load_tables(t, options);
            loaded.print(o);
            if (options.check) code = check_table(t, loaded, options, o).failed > 0 ? 1 : 0;
          },
          out);
      return code;
    }
    known += (known.empty() ? "" : ", ") + t.name;
  }
  if (name.empty()) {
    for (const auto& t : tables) out << t.name << "  " << t.summary << "\n";
    return 0;
  }
  throw ConfigError("tables: unknown table '" + name + "'; known: " + known);
}

int print_available_tables(const TablesOptions& options, std::ostream& out,
                           const std::vector<std::filesystem::path>* ran) {
  std::vector<std::filesystem::path> ran_files;
  if (ran) {
    for (const auto& f : *ran) ran_files.push_back(std::filesystem::weakly_canonical(f));
  }
  int code = 0;
  TableCheck total;
  std::size_t checked_tables = 0;
  for (const auto& t : registered_tables()) {
    LoadedTables loaded;
    try {
      if (ran && !table_related(t, options, ran_files)) continue;
      loaded = load_tables(t, options);
      loaded.print(out);
    } catch (const Error& e) {
      // Missing or failed inputs: the runs' summary above stands; say why
      // the table is absent (`cnclab tables NAME` reports it as an error).
      out << "\n(table " << t.name << " not printed: " << e.what() << ")\n";
      continue;
    }
    if (!options.check) continue;
    try {
      const TableCheck c = check_table(t, loaded, options, out);
      total.passed += c.passed;
      total.failed += c.failed;
      total.unchecked += c.unchecked;
      checked_tables += c.declared ? 1 : 0;
      if (c.failed > 0) code = std::max(code, 1);
    } catch (const ConfigError& e) {
      out << "\n(targets of table " << t.name << " not checked: " << e.what() << ")\n";
      code = 2;
    } catch (const Error& e) {
      out << "\n(targets of table " << t.name << " not checked: " << e.what() << ")\n";
      code = std::max(code, 1);
    }
  }
  if (options.check) {
    out << "\ntargets: " << total.passed << " PASS, " << total.failed << " FAIL";
    if (total.unchecked > 0) out << ", " << total.unchecked << " not declared for this profile";
    out << " (" << checked_tables << " table(s) with targets)\n";
  }
  return code;
}

}  // namespace cnclab
