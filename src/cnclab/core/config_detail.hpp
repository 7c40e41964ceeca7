#pragma once
// Internal to cnclab_core: what config.cpp (document) and config_reader.cpp
// (reader) both need. Not part of the public API.
#include <string>

namespace cnclab::config_detail {

// The dotted name of `key` below `prefix`: "prefix.key", or "key" at the top.
std::string join(const std::string& prefix, const std::string& key);

}  // namespace cnclab::config_detail
