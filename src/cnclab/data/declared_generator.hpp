#pragma once
// Reading a generator whose options are declared once (core/fields.hpp).
#include <memory>
#include <utility>

#include "cnclab/core/fields.hpp"
#include "cnclab/data/generator.hpp"

namespace cnclab {

// The declared keys read over Options' defaults, Options::validate() failing
// at the options section's position, then Generator(options).
template <class Generator, class Options>
std::shared_ptr<const DatasetGenerator> read_declared_generator(const ConfigReader& r,
                                                                const FieldList<Options>& fields) {
  Options o;
  fields.read(r, o);
  r.validate([&] { o.validate(); });
  return std::make_shared<Generator>(std::move(o));
}

}  // namespace cnclab
