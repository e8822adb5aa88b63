#pragma once
/// Deterministic, platform-independent randomness for the simulator: every random decision is
/// derived from the user's seed by hashing, so worlds and scans are reproducible bit for bit and
/// independent of thread scheduling.

#include <cmath>
#include <cstdint>

namespace litamin2::sim {

/// SplitMix64 finaliser: a bijective 64-bit mixing function.
inline std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// Combines a hash with another value (order matters).
inline std::uint64_t hash_combine(std::uint64_t h, std::uint64_t v) {
  return mix64(h ^ (mix64(v) + 0x632be59bd9b4e019ULL + (h << 6) + (h >> 2)));
}

/// Small deterministic pseudo-random generator (SplitMix64 stream).
class Rng {
 public:
  /// Starts a stream from a seed (any value, including 0).
  explicit Rng(std::uint64_t seed) : state_(mix64(seed)) {}

  /// Next raw 64-bit value.
  std::uint64_t next() {
    state_ += 0x9e3779b97f4a7c15ULL;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

  /// Uniform integer in [lo, hi] (inclusive).
  int uniform_int(int lo, int hi) {
    return lo + static_cast<int>(next() % static_cast<std::uint64_t>(hi - lo + 1));
  }

  /// True with probability p.
  bool chance(double p) { return uniform() < p; }

  /// Standard normal sample (Box-Muller; one value per call).
  double normal() {
    const double u1 = 1.0 - uniform();  // (0, 1]
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }

 private:
  std::uint64_t state_;
};

}  // namespace litamin2::sim
