// SplitMix64: a tiny seeded generator whose output is fixed by its definition (no <random>
// distributions, whose results differ between standard libraries), so hash families, samples and
// with them every index and trellis are the same on every platform for a given seed.
// Thread-safety: a value type; one generator per thread.
#pragma once

#include <cmath>
#include <cstdint>

namespace motif {

class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}
  uint64_t Next() {
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  // Uniform in (0, 1).
  double Uniform() { return (static_cast<double>(Next() >> 11) + 0.5) * 0x1.0p-53; }
  // Uniform in [0, bound) (bound > 0; the modulo bias is negligible for bound << 2^64).
  uint64_t Below(uint64_t bound) { return Next() % bound; }
  // Standard normal (Box-Muller).
  double Gaussian() {
    const double radius = std::sqrt(-2.0 * std::log(Uniform()));
    return radius * std::cos(2.0 * M_PI * Uniform());
  }

 private:
  uint64_t state_;
};

}  // namespace motif
