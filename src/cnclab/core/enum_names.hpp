#pragma once
// An enum's text names, declared once as a table that both printing and
// parsing read:
//   constexpr EnumName<Scaling> kScalingNames[] = {{Scaling::zscore, "zscore"}, ...};
//   enum_name(kScalingNames, s)           -> "zscore" ("?" for a value not listed)
//   enum_value(kScalingNames, "minmax")   -> Scaling::minmax (nullopt when unknown)
// Round-trip tests over each table stand in for the switch's -Wswitch check.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace cnclab {

template <class E>
struct EnumName {
  E value;
  const char* name;
};

template <class E, std::size_t N>
constexpr const char* enum_name(const EnumName<E> (&names)[N], E value,
                                const char* unknown = "?") noexcept {
  for (const auto& n : names) {
    if (n.value == value) return n.name;
  }
  return unknown;
}

template <class E, std::size_t N>
constexpr std::optional<E> enum_value(const EnumName<E> (&names)[N],
                                      std::string_view text) noexcept {
  for (const auto& n : names) {
    if (text == n.name) return n.value;
  }
  return std::nullopt;
}

// "a, b, c": every name, for messages.
template <class E, std::size_t N>
std::string enum_name_list(const EnumName<E> (&names)[N]) {
  std::string list;
  for (const auto& n : names) {
    if (!list.empty()) list += ", ";
    list += n.name;
  }
  return list;
}

}  // namespace cnclab
