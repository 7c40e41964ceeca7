#pragma once
// Command-line overrides `a.b.c=value`. The value is parsed as YAML, so
// `1e-4` is a number, `true` a boolean and `[28, 20]` a list; quote a string
// that would otherwise be read as another type (`name='1e3'`).
#include <yaml-cpp/yaml.h>

#include <string>
#include <string_view>
#include <vector>

namespace cnclab {

struct Override {
  std::vector<std::string> path;  // {"trainer", "momentum"}
  YAML::Node value;
  std::string text;  // the override as given, for messages

  std::string dotted_key() const;
};

// Parses one `key=value`. Throws ConfigError naming the text on an empty or
// malformed key (empty segment, characters outside [A-Za-z0-9_-]), a missing
// '=', an empty value or a value that is not valid YAML.
Override parse_override(std::string_view text);

}  // namespace cnclab
