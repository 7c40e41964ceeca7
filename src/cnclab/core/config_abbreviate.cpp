#include "cnclab/core/config_abbreviate.hpp"

#include <yaml-cpp/yaml.h>

#include <optional>
#include <vector>

#include "cnclab/core/config.hpp"
#include "cnclab/core/hash.hpp"

namespace cnclab {
namespace {

// The number of scalars in an array (a sequence of scalars and arrays), or
// nullopt when `node` is not one (a map inside, or empty nesting only).
std::optional<std::size_t> array_size(const YAML::Node& node) {
  if (node.IsScalar()) return 1;
  if (!node.IsSequence()) return std::nullopt;
  std::size_t n = 0;
  for (const auto& item : node) {
    const auto k = array_size(item);
    if (!k) return std::nullopt;
    n += *k;
  }
  return n;
}

// Lengths down the nesting when every level is regular (16, 16, 3), else empty.
std::vector<std::size_t> regular_shape(const YAML::Node& node) {
  if (!node.IsSequence()) return {};
  std::vector<std::size_t> shape = {node.size()};
  if (node.size() == 0 || node[0].IsScalar()) {
    for (const auto& item : node) {
      if (!item.IsScalar()) return {};
    }
    return shape;
  }
  const std::vector<std::size_t> inner = regular_shape(node[0]);
  if (inner.empty()) return {};
  for (const auto& item : node) {
    if (regular_shape(item) != inner) return {};
  }
  shape.insert(shape.end(), inner.begin(), inner.end());
  return shape;
}

std::string summary(const YAML::Node& array, std::size_t scalars) {
  const std::vector<std::size_t> shape = regular_shape(array);
  std::string s;
  if (shape.size() == 1) {
    s = std::to_string(shape[0]) + " values";
  } else if (shape.size() > 1) {
    for (std::size_t i = 0; i < shape.size(); ++i) s += (i ? " × " : "") + std::to_string(shape[i]);
  } else {
    s = std::to_string(array.size()) + " items, " + std::to_string(scalars) + " values";
  }
  return s + ", hash " + hash_hex(node_text(array)).substr(0, 8);
}

// Replaces, below `node`, every array over the limit by its summary.
std::size_t abbreviate(YAML::Node node, std::size_t max_scalars) {
  std::size_t count = 0;
  const auto visit = [&](YAML::Node child, const auto& replace) {
    const auto n = array_size(child);
    if (child.IsSequence() && n && *n > max_scalars) {
      replace(YAML::Node(summary(child, *n)));
      ++count;
    } else if (child.IsMap() || child.IsSequence()) {
      count += abbreviate(child, max_scalars);
    }
  };
  if (node.IsMap()) {
    for (auto it = node.begin(); it != node.end(); ++it) {
      const YAML::Node key = it->first;
      visit(it->second, [&](const YAML::Node& s) { node[key] = s; });
    }
  } else if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      visit(node[i], [&](const YAML::Node& s) { node[i] = s; });
    }
  }
  return count;
}

}  // namespace

AbbreviatedConfig abbreviate_config(const std::string& yaml_text, std::size_t max_scalars) {
  AbbreviatedConfig out{yaml_text, 0};
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception&) {
    return out;
  }
  out.abbreviated = abbreviate(root, max_scalars);
  if (out.abbreviated == 0) return out;
  YAML::Emitter emitter;
  emitter << root;
  out.text = std::string(emitter.c_str()) + "\n";
  return out;
}

}  // namespace cnclab
