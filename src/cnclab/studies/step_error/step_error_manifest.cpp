#include "cnclab/studies/step_error/step_error_manifest.hpp"

#include <algorithm>
#include <cmath>

#include "cnclab/core/config.hpp"
#include "cnclab/report/tables.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

fs::path read_path(const ConfigReader& r, const std::string& key) {
  const auto text = r.require<std::string>(key);
  return resolve_config_path(r.location(key).file, text);
}

// {number: file}: keep probabilities or fine-tune percentages.
std::map<double, fs::path> read_numbered(const ConfigReader& r, const std::string& key) {
  const ConfigReader s = r.section(key);
  std::map<double, fs::path> files;
  for (const auto& k : s.keys()) {
    double v = NAN;
    try {
      std::size_t used = 0;
      v = std::stod(k, &used);
      if (used != k.size()) v = NAN;
    } catch (const std::exception&) {
    }
    if (!std::isfinite(v)) s.fail(k, "key must be a number");
    files[v] = read_path(s, k);
  }
  if (files.empty()) r.fail(key, "must map numbers to experiment files");
  return files;
}

}  // namespace

StudyManifest read_step_error_manifest(const fs::path& file) {
  if (!fs::exists(file)) throw MissingResults(file.string() + ": study manifest not found");
  const ConfigDocument doc = ConfigDocument::load(file);
  const ConfigReader root = doc.root();
  StudyManifest m;
  const ConfigReader variants = root.section("variants");
  for (const auto& name : variants.keys()) {
    const ConfigReader v = variants.section(name);
    StudyVariant s;
    s.name = name;
    s.note = v.get<std::string>("note", "");
    s.table2 = read_numbered(v, "table2");
    s.surface1 = read_path(v, "surface1");
    s.surface1_no_dropout = read_path(v, "surface1_no_dropout");
    s.surface2 = read_numbered(v, "surface2");
    s.surface3 = read_numbered(v, "surface3");
    m.variants.push_back(std::move(s));
  }
  if (m.variants.empty() || m.variants.front().name != "paper") {
    root.fail("variants", "must start with the variant 'paper'");
  }
  const ConfigReader n = root.section("normaliser");
  m.normaliser_default = n.require<std::string>("default");
  if (m.normaliser_default != "keep" && m.normaliser_default != "refit") {
    n.fail("default", "must be keep or refit");
  }
  for (const char* choice : {"keep", "refit"}) {
    const ConfigReader c = n.section(choice);
    m.normaliser.push_back({choice, read_path(c, "surface2"), read_path(c, "surface3")});
  }
  if (root.has("repeats")) {
    const ConfigReader r = root.section("repeats");
    StudyRepeats rep;
    rep.variant = r.require<std::string>("variant");
    const bool known = std::any_of(m.variants.begin(), m.variants.end(),
                                   [&](const StudyVariant& v) { return v.name == rep.variant; });
    if (!known) r.fail("variant", "must name one of the variants");
    rep.table2 = read_path(r, "table2");
    rep.surface1 = read_path(r, "surface1");
    rep.surface2_ft15 = read_path(r, "surface2_ft15");
    rep.surface3_ft15 = read_path(r, "surface3_ft15");
    m.repeats = std::move(rep);
  }
  // The study's targets: read by `--check` (report/targets.hpp), not here.
  if (root.has("targets")) root.raw("targets");
  doc.check_all_consumed();
  return m;
}

}  // namespace cnclab
