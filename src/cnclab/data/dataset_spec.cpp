#include "cnclab/data/dataset_spec.hpp"

namespace cnclab {

DatasetSpec read_dataset_spec(const ConfigReader& r) {
  DatasetSpec spec;
  spec.generator = read_generator(r);
  spec.seed = r.optional<std::uint64_t>("seed");
  spec.targets = r.get<std::vector<std::string>>("targets", spec.targets);
  return spec;
}

}  // namespace cnclab
