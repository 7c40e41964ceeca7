// ConfigReader: typed, located reads of one section of a ConfigDocument, and
// the decoding of YAML scalars behind ConfigReader::get/require/optional.
#include <charconv>
#include <cmath>

#include "cnclab/core/config.hpp"
#include "cnclab/core/config_detail.hpp"
#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

bool parse_int_text(const std::string& s, std::int64_t& out) {
  const char* begin = s.data();
  const char* end = s.data() + s.size();
  if (begin != end && *begin == '+') ++begin;
  auto [ptr, ec] = std::from_chars(begin, end, out);
  return ec == std::errc() && ptr == end && begin != end;
}

bool is_plain_scalar(const YAML::Node& n) {
  return n.IsScalar() && n.Tag() != "!";
}

}  // namespace

// ---------------------------------------------------------------- reader

ConfigReader::ConfigReader(const ConfigDocument& doc, YAML::Node node, std::string path)
    : doc_(&doc), node_(std::move(node)), path_(std::move(path)) {}

YAML::Node ConfigReader::child(const std::string& key) const {
  if (!node_.IsMap()) return YAML::Node();
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    if (it->first.Scalar() == key) return it->second;
  }
  return YAML::Node();
}

void ConfigReader::mark(const std::string& key) const {
  doc_->state_->consumed.insert(dotted(key));
}

bool ConfigReader::has(const std::string& key) const {
  mark(key);
  const YAML::Node n = child(key);
  return n.IsDefined() && !n.IsNull();
}

ConfigReader ConfigReader::section(const std::string& key) const {
  mark(key);
  YAML::Node n = child(key);
  if (!n.IsDefined() || n.IsNull())
    return ConfigReader(*doc_, YAML::Node(YAML::NodeType::Map), dotted(key));
  if (!n.IsMap()) fail(key, "expected a section (a map of keys)");
  return ConfigReader(*doc_, n, dotted(key));
}

YAML::Node ConfigReader::raw(const std::string& key) const {
  mark(key);
  doc_->state_->consumed.insert(dotted(key) + "/*");
  return child(key);
}

ConfigReader ConfigReader::element(const std::string& key, std::size_t index) const {
  const YAML::Node list = child(key);
  if (!list.IsSequence() || index >= list.size() || !list[index].IsMap()) {
    fail(key, "entry " + std::to_string(index) + " must be a map");
  }
  return ConfigReader(*doc_, list[index], dotted(key) + "[" + std::to_string(index) + "]");
}

std::vector<std::string> ConfigReader::keys() const {
  std::vector<std::string> out;
  if (!node_.IsMap()) return out;
  for (auto it = node_.begin(); it != node_.end(); ++it) out.push_back(it->first.Scalar());
  return out;
}

std::string ConfigReader::dotted(const std::string& key) const {
  return config_detail::join(path_, key);
}

SourceLocation ConfigReader::location(const std::string& key) const {
  return doc_->location(dotted(key));
}

void ConfigReader::fail(const std::string& key, const std::string& rule) const {
  const YAML::Node n = child(key);
  std::string msg = location(key).str() + ": " + dotted(key);
  if (n.IsDefined() && !n.IsNull()) msg += " = " + node_text(n);
  throw ConfigError(msg + ": " + rule);
}

void ConfigReader::rethrow_option_error(const OptionError& e) const {
  const std::string key = dotted(e.field());
  // Quote the value as the user wrote it when the field is a key of this
  // section ("1.5", not the options struct's "1.500000").
  std::string value = e.value();
  YAML::Node n = node_;
  std::size_t start = 0;
  const std::string& field = e.field();
  bool found = true;
  while (found) {
    const auto dot = field.find('.', start);
    const std::string part = field.substr(start, dot == std::string::npos ? dot : dot - start);
    YAML::Node next;
    found = false;
    if (n.IsMap()) {
      for (auto it = n.begin(); it != n.end(); ++it) {
        if (it->first.Scalar() == part) {
          next.reset(it->second);
          found = true;
          break;
        }
      }
    }
    if (!found) break;
    n.reset(next);
    if (dot == std::string::npos) {
      value = node_text(n);
      break;
    }
    start = dot + 1;
  }
  throw ConfigError(doc_->location(key).str() + ": " + key + " = " + value + ": " + e.rule());
}

// ---------------------------------------------------------------- decoding

namespace config_detail {

double decode_double(const ConfigReader& r, const std::string& key, const YAML::Node& n) {
  if (!is_plain_scalar(n)) r.fail(key, "expected a number");
  const std::string& s = n.Scalar();
  double value = 0;
  const char* begin = s.data();
  const char* end = s.data() + s.size();
  if (begin != end && *begin == '+') ++begin;
  auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec == std::errc::result_out_of_range) r.fail(key, "number out of the range of a double");
  if (ec != std::errc() || ptr != end || begin == end) r.fail(key, "expected a number");
  if (!std::isfinite(value)) r.fail(key, "must be a finite number");
  return value;
}

bool decode_bool(const ConfigReader& r, const std::string& key, const YAML::Node& n) {
  if (is_plain_scalar(n)) {
    const std::string& s = n.Scalar();
    if (s == "true" || s == "True" || s == "TRUE") return true;
    if (s == "false" || s == "False" || s == "FALSE") return false;
  }
  r.fail(key, "expected true or false");
}

std::string decode_string(const ConfigReader& r, const std::string& key, const YAML::Node& n) {
  if (!n.IsScalar()) r.fail(key, "expected a string");
  return n.Scalar();
}

std::int64_t decode_int(const ConfigReader& r, const std::string& key, const YAML::Node& n) {
  std::int64_t value = 0;
  if (!is_plain_scalar(n) || !parse_int_text(n.Scalar(), value)) {
    r.fail(key, "expected an integer");
  }
  return value;
}

std::uint64_t decode_uint(const ConfigReader& r, const std::string& key, const YAML::Node& n) {
  if (!is_plain_scalar(n)) r.fail(key, "expected a non-negative integer");
  const std::string& s = n.Scalar();
  std::uint64_t value = 0;
  const char* begin = s.data();
  const char* end = s.data() + s.size();
  if (begin != end && *begin == '+') ++begin;
  auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec == std::errc::result_out_of_range) r.fail(key, "integer too large");
  if (ec != std::errc() || ptr != end || begin == end)
    r.fail(key, "expected a non-negative integer");
  return value;
}

void require_sequence(const ConfigReader& r, const std::string& key, const YAML::Node& n) {
  if (!n.IsSequence()) r.fail(key, "expected a list, e.g. [28, 20]");
}

}  // namespace config_detail
}  // namespace cnclab
