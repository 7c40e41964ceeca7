#pragma once
// Content hashing for cache keys and trial identities: FNV-1a over bytes,
// 64-bit, printed as 16 hex digits. Not cryptographic; collisions between the
// few thousand configs of a study are negligible (birthday bound ~2^-40).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace cnclab {

class Hasher {
 public:
  Hasher& add(std::string_view bytes);
  Hasher& add(std::span<const double> values);
  Hasher& add(std::uint64_t value);
  std::uint64_t value() const { return h_; }
  // 16 lower-case hex digits.
  std::string hex() const;

 private:
  std::uint64_t h_ = 0xCBF29CE484222325ULL;  // FNV-1a 64-bit offset basis
};

inline std::string hash_hex(std::string_view bytes) {
  return Hasher().add(bytes).hex();
}

// hash_hex of a file's bytes, read in chunks; nullopt when it cannot be read.
std::optional<std::string> file_hash_hex(const std::filesystem::path& file);

}  // namespace cnclab
