#pragma once
// Seeded random streams. There is no global RNG: a master seed derives one
// independent stream per consumer name ("split", "init", "dropout", ...), so
// adding a consumer never changes the numbers another one sees.
//
// Generator: xoshiro256** (Blackman & Vigna 2018), seeded through SplitMix64.
// Distributions are implemented here rather than with <random>'s, whose
// algorithms are implementation-defined: the same seed must give the same
// numbers with any standard library.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace cnclab {

// Seed of the stream `name` under `master`: SplitMix64(master ^ FNV-1a(name)).
std::uint64_t derive_seed(std::uint64_t master, std::string_view name);

// A master seed given as text (the command line's --seed): decimal digits
// only, optionally with a leading '+', in [0, 2^64 - 1]. Anything else, e.g.
// "-1" (which strtoull would wrap to 2^64 - 1), "1.5", "1e3" or "", throws
// ConfigError "<option> <text>: <rule>", the way `seed:` in YAML is rejected.
std::uint64_t parse_seed(const std::string& text, const std::string& option);

class Rng {
 public:
  explicit Rng(std::uint64_t seed);
  // Stream `name` derived from `master` (see derive_seed).
  Rng(std::uint64_t master, std::string_view name) : Rng(derive_seed(master, name)) {}

  std::uint64_t next_u64();
  // Uniform in [0, 1) with 53 random bits.
  double uniform();
  // Uniform in [a, b).
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  // Standard normal by the Marsaglia polar method (no cached second value, so
  // the stream position depends only on the number of calls).
  double normal();
  double normal(double mean, double std) { return mean + std * normal(); }
  // True with probability p.
  bool bernoulli(double p) { return uniform() < p; }
  // Uniform integer in [0, n), unbiased (Lemire's rejection method). n > 0.
  std::uint64_t below(std::uint64_t n);
  // Fisher-Yates shuffle.
  template <class T>
  void shuffle(std::vector<T>& v) {
    for (std::size_t i = v.size(); i > 1; --i) {
      std::size_t j = static_cast<std::size_t>(below(i));
      std::swap(v[i - 1], v[j]);
    }
  }

 private:
  std::array<std::uint64_t, 4> s_{};
};

}  // namespace cnclab
