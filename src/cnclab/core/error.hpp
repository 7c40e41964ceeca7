#pragma once
// One error family for cnclab. Bad input throws; numerical non-convergence is
// a result (a trainer Summary), never an exception.
//
// Exit codes of the CLI follow the type: ConfigError (and its subclasses) -> 2,
// any other Error -> 1.
#include <stdexcept>
#include <string>

namespace cnclab {

// Base of every error cnclab throws on purpose.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Bad configuration or usage: unknown key, wrong type, out-of-range value,
// malformed YAML, missing experiment file. The message names where.
class ConfigError : public Error {
 public:
  using Error::Error;
};

// An options struct's validate() failed. Carries the field name relative to
// the struct so the config layer can prefix the dotted key and the YAML
// location: "momentum = 1.5: must be in [0, 1)".
class OptionError : public ConfigError {
 public:
  OptionError(std::string field, std::string value, std::string rule)
      : ConfigError(field + " = " + value + ": " + rule),
        field_(std::move(field)),
        value_(std::move(value)),
        rule_(std::move(rule)) {}
  const std::string& field() const { return field_; }
  const std::string& value() const { return value_; }
  const std::string& rule() const { return rule_; }

 private:
  std::string field_;
  std::string value_;
  std::string rule_;
};

// A file that is missing, unreadable, corrupt or incomplete; a failed write.
class IoError : public Error {
 public:
  using Error::Error;
};

// Work that would exceed a resource (memory estimate, sizes) before it starts.
class ResourceError : public Error {
 public:
  using Error::Error;
};

}  // namespace cnclab
