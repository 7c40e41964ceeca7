#pragma once
// Every generator `dataset.generator` may name: data/'s own (built in,
// builtin_generators() in generator.hpp) and those added from above. A study
// adds its generator with register_generator() from its
// register_<paper>_study(), as it does job kinds and tables, so a generator
// that belongs to one paper (or needs a higher module) lives in the study's
// folder. Registration happens once, before any command runs
// (register_builtins(), the first statement of main), never from a static
// initialiser.
#include <vector>

#include "cnclab/data/generator.hpp"

namespace cnclab {

// Adds a generator defined above data/. Call it before the first dataset is
// read: dataset_fields() (dataset_spec.hpp) lists the names once.
// std::logic_error for a name already known (built in or registered).
void register_generator(GeneratorEntry entry);

// The built-in generators in their order, then the registered ones in
// registration order.
std::vector<GeneratorEntry> known_generators();

}  // namespace cnclab
