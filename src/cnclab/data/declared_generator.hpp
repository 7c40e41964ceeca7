#pragma once
// Reading a generator whose options are declared once (core/fields.hpp).
#include <memory>
#include <utility>

#include "cnclab/core/fields.hpp"
#include "cnclab/data/generator.hpp"

namespace cnclab {

// The declared keys read over Options' defaults, then Generator(options),
// whose constructor runs Options::validate(), failing at the options
// section's position. Constructed once: a step_error generator plans its
// tool path there, on a CAD face as much as a tenth of the dataset's cost
// (geometry/tool_path.hpp).
template <class Generator, class Options>
std::shared_ptr<const DatasetGenerator> read_declared_generator(const ConfigReader& r,
                                                                const FieldList<Options>& fields) {
  Options o;
  fields.read(r, o);
  std::shared_ptr<const DatasetGenerator> generator;
  r.validate([&] { generator = std::make_shared<Generator>(std::move(o)); });
  return generator;
}

}  // namespace cnclab
