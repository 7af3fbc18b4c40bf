#pragma once
// Fast deterministic random numbers for the simulator: xoshiro256** (Blackman & Vigna) seeded by
// splitmix64, plus a hash for position-stable "textures" (the same wall looks the same on every
// visit). Normal deviates come from a 4096-entry inverse-CDF table, not std::normal_distribution.
#include <array>
#include <cstdint>

namespace radarslam::sim {

constexpr std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

/// Order-dependent hash of several integers (for deterministic per-object/per-cell values).
constexpr std::uint64_t hashCombine(std::uint64_t a, std::uint64_t b) {
  return splitmix64(a ^ (splitmix64(b) + 0x632BE59BD9B4E019ULL));
}

/// Uniform in [0, 1) from a hash value.
inline double hashToUnit(std::uint64_t h) { return static_cast<double>(h >> 11) * 0x1.0p-53; }

class Rng {
 public:
  explicit Rng(std::uint64_t seed) {
    std::uint64_t x = seed;
    for (auto& w : s_) w = splitmix64(x += 0x9E3779B97F4A7C15ULL);
  }
  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Integer in [0, n).
  std::uint32_t below(std::uint32_t n) { return static_cast<std::uint32_t>(((next() >> 32) * n) >> 32); }
  bool chance(double p) { return uniform() < p; }
  /// Standard normal deviate (table-based, accurate to ~1e-3 sigma; tails clipped at ~3.5 sigma).
  float normal();

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::array<std::uint64_t, 4> s_{};
};

/// Table of standard normal quantiles at (i + 0.5) / 4096, for 12-bit indices.
const std::array<float, 4096>& normalTable();

inline float Rng::normal() { return normalTable()[next() >> 52]; }

}  // namespace radarslam::sim
