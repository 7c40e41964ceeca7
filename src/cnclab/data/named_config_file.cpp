#include "cnclab/data/named_config_file.hpp"

namespace cnclab {

std::filesystem::path named_config_file(const ConfigReader& r, const std::string& key) {
  const YAML::Node node = r.raw(key);
  if (!node.IsScalar()) r.fail(key, "expected a file name or a map");
  const SourceLocation where = r.location(key);
  if (where.line == 0) return node.Scalar();
  const ConfigLookup lookup =
      lookup_config_path(where.file, node.Scalar(), ConfigSearch::from_environment());
  if (!lookup.found) r.fail(key, lookup.not_found_message());
  return *lookup.found;
}

}  // namespace cnclab
