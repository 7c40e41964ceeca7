// ConfigDocument: loading a config file with its includes, profiles,
// overrides, key locations and the check that every key was read. Where
// named files are searched: config_lookup.cpp; typed reading:
// config_reader.cpp.
#include "cnclab/core/config.hpp"

#include <algorithm>
#include <fstream>
#include <functional>
#include <sstream>

#include "cnclab/core/config_detail.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/suggest.hpp"

namespace cnclab {
namespace fs = std::filesystem;

namespace config_detail {

std::string join(const std::string& prefix, const std::string& key) {
  return prefix.empty() ? key : prefix + "." + key;
}

}  // namespace config_detail

namespace {

// Include nesting and tree size limits: a config is hand-written and small;
// these only stop include cycles and YAML alias bombs.
constexpr int kMaxIncludeDepth = 16;
constexpr std::size_t kMaxNodes = 200000;
// Nesting limit: bounds the recursion of every tree walk (a self-referencing
// alias such as `&a [*a]` is infinitely deep). Found by fuzzing.
constexpr int kMaxDepth = 64;

SourceLocation mark_location(const std::string& file, const YAML::Mark& mark) {
  if (mark.is_null()) return {file, 0, 0};
  return {file, mark.line + 1, mark.column + 1};
}

void erase_below(std::map<std::string, SourceLocation>& locations, const std::string& key) {
  const std::string prefix = key + ".";
  for (auto it = locations.lower_bound(prefix);
       it != locations.end() && it->first.compare(0, prefix.size(), prefix) == 0;) {
    it = locations.erase(it);
  }
}

// Records the location of every map key below `node` and rejects what a
// config may not contain: non-scalar or duplicate keys, oversized trees.
void index_tree(const YAML::Node& node, const std::string& prefix, const std::string& file,
                std::map<std::string, SourceLocation>& out, std::size_t& count, int depth = 0) {
  if (depth > kMaxDepth) {
    throw ConfigError(mark_location(file, node.Mark()).str() + ": " +
                      (prefix.empty() ? std::string("config") : prefix) + ": nested deeper than " +
                      std::to_string(kMaxDepth) + " levels (recursive alias?)");
  }
  if (++count > kMaxNodes) {
    throw ConfigError(file + ": config has more than " + std::to_string(kMaxNodes) +
                      " nodes (alias expansion?)");
  }
  if (node.IsSequence()) {
    for (const auto& item : node) index_tree(item, prefix, file, out, count, depth + 1);
    return;
  }
  if (!node.IsMap()) return;
  std::set<std::string> seen;
  for (auto it = node.begin(); it != node.end(); ++it) {
    // Copies, not references: yaml-cpp's iterator returns a temporary proxy
    // whose members die with the full expression.
    const YAML::Node key = it->first;
    if (!key.IsScalar()) {
      throw ConfigError(mark_location(file, key.Mark()).str() + ": " +
                        (prefix.empty() ? std::string("top level") : prefix) +
                        ": map keys must be plain names");
    }
    const std::string dotted = config_detail::join(prefix, key.Scalar());
    if (!seen.insert(key.Scalar()).second) {
      throw ConfigError(mark_location(file, key.Mark()).str() + ": " + dotted + ": duplicate key");
    }
    const YAML::Node value = it->second;
    out[dotted] = mark_location(file, value.IsScalar() ? value.Mark() : key.Mark());
    index_tree(value, dotted, file, out, count, depth + 1);
  }
}

// yaml-cpp's const operator[] returns an invalid node for a missing key, on
// which IsMap() throws.
bool is_map(const YAML::Node& n) {
  return n.IsDefined() && n.IsMap();
}

// dst <- src, key by key for maps; anything else replaces.
void merge_into(YAML::Node& dst, const YAML::Node& src) {
  for (auto it = src.begin(); it != src.end(); ++it) {
    const std::string key = it->first.Scalar();
    YAML::Node existing = dst[key];
    if (existing.IsMap() && it->second.IsMap()) {
      merge_into(existing, it->second);
    } else {
      dst[key] = YAML::Clone(it->second);
    }
  }
}

void merge_locations(std::map<std::string, SourceLocation>& dst, const YAML::Node& dst_tree,
                     const std::map<std::string, SourceLocation>& src, const YAML::Node& src_tree,
                     const std::string& prefix) {
  for (auto it = src_tree.begin(); it != src_tree.end(); ++it) {
    const std::string key = it->first.Scalar();
    const std::string dotted = config_detail::join(prefix, key);
    const YAML::Node existing = dst_tree[key];
    if (!(is_map(existing) && it->second.IsMap())) erase_below(dst, dotted);
    if (auto loc = src.find(dotted); loc != src.end()) dst[dotted] = loc->second;
    if (it->second.IsMap()) {
      // Children: copy all located keys below `dotted` from src.
      const std::string below = dotted + ".";
      for (auto s = src.lower_bound(below);
           s != src.end() && s->first.compare(0, below.size(), below) == 0; ++s) {
        dst[s->first] = s->second;
      }
    }
  }
}

YAML::Node parse_yaml(const std::string& text, const std::string& origin) {
  try {
    YAML::Node node = YAML::Load(text);
    if (!node.IsDefined() || node.IsNull()) return YAML::Node(YAML::NodeType::Map);
    if (!node.IsMap()) {
      throw ConfigError(mark_location(origin, node.Mark()).str() +
                        ": the top level of a config must be a map of keys");
    }
    return node;
  } catch (const YAML::ParserException& e) {
    throw ConfigError(mark_location(origin, e.mark).str() + ": malformed YAML: " + e.msg);
  } catch (const YAML::Exception& e) {
    throw ConfigError(origin + ": malformed YAML: " + e.msg);
  }
}

std::string read_text(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) {
    throw ConfigError(file.string() + ": " +
                      (fs::exists(file, ec) ? "not a regular file" : "no such file"));
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ConfigError(file.string() + ": cannot open for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Loaded {
  YAML::Node tree;
  std::map<std::string, SourceLocation> locations;
};

Loaded load_recursive(const fs::path& file, const ConfigSearch& search,
                      std::vector<fs::path>& stack) {
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(file, ec);
  if (std::find(stack.begin(), stack.end(), canonical) != stack.end()) {
    throw ConfigError(file.string() + ": include cycle");
  }
  if (static_cast<int>(stack.size()) >= kMaxIncludeDepth) {
    throw ConfigError(file.string() + ": includes nested deeper than " +
                      std::to_string(kMaxIncludeDepth));
  }
  const std::string origin = file.string();
  YAML::Node own = parse_yaml(read_text(file), origin);
  std::map<std::string, SourceLocation> own_locations;
  std::size_t count = 0;
  index_tree(own, "", origin, own_locations, count);

  std::vector<std::string> includes;
  std::string where;  // of the include key, for a name found nowhere
  if (own["include"]) {
    const YAML::Node inc = own["include"];
    where = own_locations["include"].str();
    if (inc.IsScalar()) {
      includes.push_back(inc.Scalar());
    } else if (inc.IsSequence()) {
      for (const auto& item : inc) {
        if (!item.IsScalar()) throw ConfigError(where + ": include: expected a list of paths");
        includes.push_back(item.Scalar());
      }
    } else {
      throw ConfigError(where + ": include: expected a path or a list of paths");
    }
    own.remove("include");
    erase_below(own_locations, "include");
    own_locations.erase("include");
  }

  Loaded result{YAML::Node(YAML::NodeType::Map), {}};
  stack.push_back(canonical);
  for (const auto& name : includes) {
    const ConfigLookup lookup = lookup_config_path(file, name, search);
    if (!lookup.found) {
      throw ConfigError(where + ": include " + name + ": " + lookup.not_found_message());
    }
    // Never assign to a YAML::Node that already refers to a node: yaml-cpp's
    // operator= rewrites the referenced node instead of rebinding.
    Loaded inc = [&] {
      try {
        return load_recursive(*lookup.found, search, stack);
      } catch (const ConfigError& e) {
        throw ConfigError(std::string(e.what()) + " (included from " + origin + ")");
      }
    }();
    merge_locations(result.locations, result.tree, inc.locations, inc.tree, "");
    merge_into(result.tree, inc.tree);
  }
  stack.pop_back();
  merge_locations(result.locations, result.tree, own_locations, own, "");
  merge_into(result.tree, own);
  return result;
}

}  // namespace

std::string node_text(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "null";
  if (node.IsScalar()) return node.Scalar();
  YAML::Emitter out;
  out << YAML::Flow << node;
  return out.c_str();
}

// ---------------------------------------------------------------- document

ConfigDocument ConfigDocument::load(const fs::path& file, const std::string& profile,
                                    const ConfigSearch& search) {
  std::vector<fs::path> stack;
  Loaded loaded = load_recursive(file, search, stack);
  ConfigDocument doc;
  doc.tree_ = loaded.tree;
  doc.origin_ = file.string();
  doc.state_->locations = std::move(loaded.locations);
  doc.take_profiles(profile);
  return doc;
}

ConfigDocument ConfigDocument::parse(const std::string& yaml_text, const std::string& origin,
                                     const std::string& profile) {
  ConfigDocument doc;
  doc.tree_ = parse_yaml(yaml_text, origin);
  doc.origin_ = origin;
  std::size_t count = 0;
  index_tree(doc.tree_, "", origin, doc.state_->locations, count);
  doc.take_profiles(profile);
  return doc;
}

void ConfigDocument::take_profiles(const std::string& profile) {
  const YAML::Node profiles = static_cast<const YAML::Node&>(tree_)["profiles"];
  if (!profiles.IsDefined()) return;
  const auto fail = [&](const std::string& key, const std::string& why) {
    throw ConfigError(location(key).str() + ": " + key + ": " + why);
  };
  if (!profiles.IsMap()) fail("profiles", "must be a map of profile names to overrides");
  std::vector<Override> chosen;
  for (auto it = profiles.begin(); it != profiles.end(); ++it) {
    const std::string name = it->first.as<std::string>();
    const std::string key = "profiles." + name;
    profiles_.push_back(name);
    if (it->second.IsNull()) continue;
    if (!it->second.IsMap()) fail(key, "must be a map of `dotted.key: value` overrides");
    for (auto e = it->second.begin(); e != it->second.end(); ++e) {
      const std::string dotted = e->first.as<std::string>();
      const std::string where = location(key + "." + dotted).str();
      if (!e->second.IsDefined() || e->second.IsNull()) fail(key + "." + dotted, "value is null");
      if (dotted.rfind("profile.", 0) == 0) {  // a setting of the profile, not an override
        if (dotted != "profile.exclusive") {
          fail(key + "." + dotted, "unknown profile setting (the one there is: profile.exclusive)");
        }
        bool exclusive = false;
        if (!e->second.IsScalar() || !YAML::convert<bool>::decode(e->second, exclusive)) {
          fail(key + "." + dotted, "must be true or false, not " + node_text(e->second));
        }
        if (exclusive) exclusive_profiles_.push_back(name);
        continue;
      }
      // parse_override checks the key; the value is the YAML node itself.
      Override o;
      try {
        o = parse_override(dotted + "=0");
      } catch (const ConfigError&) {
        fail(key + "." + dotted,
             "is not a dotted key (letters, digits, '_', '-', '.' between segments)");
      }
      o.value = YAML::Clone(e->second);
      o.text = "profile " + name + " (" + where + "): " + dotted + "=" + node_text(e->second);
      if (name == profile) chosen.push_back(std::move(o));
    }
  }
  tree_.remove("profiles");
  for (const auto& o : chosen) apply(o);
}

void ConfigDocument::apply(const Override& override) {
  const SourceLocation where{"override " + override.text, 0, 0};
  // Recursive so that each level binds a fresh YAML::Node (see load_recursive).
  std::function<void(YAML::Node, std::size_t, const std::string&)> set =
      [&](YAML::Node node, std::size_t i, const std::string& prefix) {
        const std::string& part = override.path[i];
        const std::string dotted = config_detail::join(prefix, part);
        if (i + 1 == override.path.size()) {
          node[part] = YAML::Clone(override.value);
          return;
        }
        const YAML::Node existing = static_cast<const YAML::Node&>(node)[part];
        if (!existing.IsDefined() || existing.IsNull()) {
          node[part] = YAML::Node(YAML::NodeType::Map);
          state_->locations[dotted] = where;
        } else if (!existing.IsMap()) {
          throw ConfigError(where.str() + ": " + dotted + " is " + node_text(existing) +
                            ", not a section, so it has no key '" + override.path[i + 1] + "'");
        }
        set(node[part], i + 1, dotted);
      };
  set(tree_, 0, "");
  const std::string key = override.dotted_key();
  erase_below(state_->locations, key);
  state_->locations[key] = where;
  std::size_t count = 0;
  std::map<std::string, SourceLocation> below;
  index_tree(override.value, key, where.file, below, count);
  for (auto& [k, loc] : below) state_->locations[k] = where;
}

ConfigReader ConfigDocument::root() const {
  return ConfigReader(*this, tree_, "");
}

std::string ConfigDocument::to_yaml() const {
  YAML::Emitter out;
  out << tree_;
  return std::string(out.c_str()) + "\n";
}

SourceLocation ConfigDocument::location(const std::string& dotted_key) const {
  std::string key = dotted_key;
  while (!key.empty()) {
    if (auto it = state_->locations.find(key); it != state_->locations.end()) return it->second;
    const auto dot = key.rfind('.');
    key = dot == std::string::npos ? std::string() : key.substr(0, dot);
  }
  return {origin_, 0, 0};
}

void ConfigDocument::check_all_consumed() const {
  const auto& known = state_->consumed;
  std::function<void(const YAML::Node&, const std::string&)> walk = [&](const YAML::Node& node,
                                                                        const std::string& prefix) {
    if (!node.IsMap()) return;
    for (auto it = node.begin(); it != node.end(); ++it) {
      const std::string dotted = config_detail::join(prefix, it->first.Scalar());
      if (known.count(dotted + "/*")) continue;  // consumed whole (raw)
      if (!known.count(dotted)) {
        // Suggest the closest key the readers asked for at this level.
        std::vector<std::string> here;
        std::string allowed;
        const std::string parent = prefix.empty() ? "" : prefix + ".";
        for (const auto& k : known) {
          if (k.compare(0, parent.size(), parent) != 0) continue;
          const std::string rest = k.substr(parent.size());
          if (rest.empty() || rest.find('.') != std::string::npos ||
              rest.find('/') != std::string::npos) {
            continue;
          }
          allowed += (allowed.empty() ? "" : ", ") + rest;
          here.push_back(rest);
        }
        std::string msg = location(dotted).str() + ": " + dotted + ": unknown key" +
                          did_you_mean(it->first.Scalar(), here);
        if (!allowed.empty()) msg += "; allowed here: " + allowed;
        throw ConfigError(msg);
      }
      walk(it->second, dotted);
    }
  };
  walk(tree_, "");
}

}  // namespace cnclab
