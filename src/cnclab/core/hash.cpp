#include "cnclab/core/hash.hpp"

#include <cstring>
#include <fstream>

namespace cnclab {

Hasher& Hasher::add(std::string_view bytes) {
  for (unsigned char c : bytes) {
    h_ ^= c;
    h_ *= 0x100000001B3ULL;  // FNV-1a 64-bit prime
  }
  return *this;
}

Hasher& Hasher::add(std::span<const double> values) {
  return add(std::string_view(reinterpret_cast<const char*>(values.data()),
                              values.size() * sizeof(double)));
}

Hasher& Hasher::add(std::uint64_t value) {
  char bytes[sizeof value];
  std::memcpy(bytes, &value, sizeof value);
  return add(std::string_view(bytes, sizeof bytes));
}

std::string Hasher::hex() const {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out(16, '0');
  for (int i = 0; i < 16; ++i) out[15 - i] = kDigits[(h_ >> (4 * i)) & 0xF];
  return out;
}

std::optional<std::string> file_hash_hex(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  Hasher h;  // FNV-1a runs byte by byte: chunks hash as the whole file does
  std::string buffer(1 << 20, '\0');
  while (in.read(buffer.data(), static_cast<std::streamsize>(buffer.size())) || in.gcount() > 0) {
    h.add(std::string_view(buffer.data(), static_cast<std::size_t>(in.gcount())));
  }
  if (in.bad()) return std::nullopt;
  return h.hex();
}

}  // namespace cnclab
