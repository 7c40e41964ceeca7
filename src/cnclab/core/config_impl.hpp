#pragma once
// Template part of config.hpp: typed decoding of YAML scalars and lists.
// Numbers are parsed from the scalar text (YAML 1.2 core schema: plain
// scalars only; a quoted "0.5" is a string), so every rule is ours and
// identical on every platform.
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace config_detail {

double decode_double(const ConfigReader& r, const std::string& key, const YAML::Node& n);
bool decode_bool(const ConfigReader& r, const std::string& key, const YAML::Node& n);
std::string decode_string(const ConfigReader& r, const std::string& key, const YAML::Node& n);
std::int64_t decode_int(const ConfigReader& r, const std::string& key, const YAML::Node& n);
std::uint64_t decode_uint(const ConfigReader& r, const std::string& key, const YAML::Node& n);
void require_sequence(const ConfigReader& r, const std::string& key, const YAML::Node& n);

template <class T>
struct Decoder;

template <>
struct Decoder<double> {
  static double decode(const ConfigReader& r, const std::string& k, const YAML::Node& n) {
    return decode_double(r, k, n);
  }
};
template <>
struct Decoder<bool> {
  static bool decode(const ConfigReader& r, const std::string& k, const YAML::Node& n) {
    return decode_bool(r, k, n);
  }
};
template <>
struct Decoder<std::string> {
  static std::string decode(const ConfigReader& r, const std::string& k, const YAML::Node& n) {
    return decode_string(r, k, n);
  }
};
template <>
struct Decoder<std::int64_t> {
  static std::int64_t decode(const ConfigReader& r, const std::string& k, const YAML::Node& n) {
    return decode_int(r, k, n);
  }
};
template <>
struct Decoder<std::uint64_t> {
  static std::uint64_t decode(const ConfigReader& r, const std::string& k, const YAML::Node& n) {
    return decode_uint(r, k, n);
  }
};
template <class T>
struct Decoder<std::vector<T>> {
  static std::vector<T> decode(const ConfigReader& r, const std::string& k, const YAML::Node& n) {
    require_sequence(r, k, n);
    std::vector<T> out;
    out.reserve(n.size());
    for (const auto& item : n) out.push_back(Decoder<T>::decode(r, k, item));
    return out;
  }
};

}  // namespace config_detail

template <class T>
std::optional<T> ConfigReader::optional(const std::string& key) const {
  mark(key);
  const YAML::Node n = child(key);
  if (!n.IsDefined() || n.IsNull()) return std::nullopt;
  return config_detail::Decoder<T>::decode(*this, key, n);
}

template <class T>
T ConfigReader::get(const std::string& key, const T& fallback) const {
  auto value = optional<T>(key);
  return value ? *value : fallback;
}

template <class T>
T ConfigReader::require(const std::string& key) const {
  auto value = optional<T>(key);
  if (!value) fail(key, "is required");
  return *value;
}

template <class F>
void ConfigReader::validate(F&& validate) const {
  try {
    validate();
  } catch (const OptionError& e) {
    rethrow_option_error(e);
  }
}

}  // namespace cnclab
