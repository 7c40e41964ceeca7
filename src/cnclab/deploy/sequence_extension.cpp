#include "cnclab/deploy/sequence_extension.hpp"

#include <deque>
#include <stdexcept>

namespace cnclab {
namespace {

// A deque: find_sequence_extension's pointers stay valid when more register.
std::deque<SequenceExtension>& extensions() {
  static std::deque<SequenceExtension> registered;
  return registered;
}

}  // namespace

void register_sequence_extension(SequenceExtension extension) {
  if (find_sequence_extension(extension.generator) != nullptr) {
    throw std::logic_error("sequence extension for generator '" + extension.generator +
                           "' registered twice");
  }
  extensions().push_back(std::move(extension));
}

const SequenceExtension* find_sequence_extension(const std::string& generator) {
  for (const auto& e : extensions()) {
    if (e.generator == generator) return &e;
  }
  return nullptr;
}

}  // namespace cnclab
