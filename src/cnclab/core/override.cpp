#include "cnclab/core/override.hpp"

#include <algorithm>
#include <string>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

bool is_key_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-';
}

[[noreturn]] void fail(std::string_view text, const std::string& why) {
  throw ConfigError("override '" + std::string(text) + "': " + why);
}

// A value with more '[' or '{' than closing ones was most likely cut at a
// space by the shell (`model.hidden=[16, 8]` unquoted arrives as
// `model.hidden=[16,`): say so.
std::string shell_split_hint(std::string_view text, std::string_view value) {
  const auto count = [&](char c) { return std::count(value.begin(), value.end(), c); };
  if (count('[') <= count(']') && count('{') <= count('}')) return "";
  return " (the shell may have split the word at a space: quote it, e.g. '" + std::string(text) +
         " ...')";
}

}  // namespace

std::string Override::dotted_key() const {
  std::string key;
  for (const auto& part : path) key += (key.empty() ? "" : ".") + part;
  return key;
}

Override parse_override(std::string_view text) {
  const auto eq = text.find('=');
  if (eq == std::string_view::npos) fail(text, "expected key=value");
  const std::string_view key = text.substr(0, eq);
  const std::string_view value = text.substr(eq + 1);
  if (key.empty()) fail(text, "empty key before '='");

  Override result;
  result.text = std::string(text);
  std::size_t start = 0;
  while (true) {
    const auto dot = key.find('.', start);
    const auto part = key.substr(start, dot == std::string_view::npos ? key.npos : dot - start);
    if (part.empty()) fail(text, "empty segment in key '" + std::string(key) + "'");
    for (char c : part) {
      if (!is_key_char(c)) {
        fail(text, "invalid character '" + std::string(1, c) + "' in key '" + std::string(key) +
                       "' (allowed: letters, digits, '_', '-', '.' between segments)");
      }
    }
    result.path.emplace_back(part);
    if (dot == std::string_view::npos) break;
    start = dot + 1;
  }
  if (value.find_first_not_of(" \t") == std::string_view::npos) {
    fail(text, "empty value after '=' (write key='' for an empty string)");
  }
  try {
    result.value = YAML::Load(std::string(value));
  } catch (const YAML::Exception& e) {
    fail(text, "value is not valid YAML: " + e.msg + shell_split_hint(text, value));
  }
  if (!result.value.IsDefined() || result.value.IsNull()) {
    // "~" or "null": an explicit null is not a value any option accepts.
    fail(text, "value is null");
  }
  return result;
}

}  // namespace cnclab
