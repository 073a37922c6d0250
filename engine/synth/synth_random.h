// SynthRandom: the synthesiser's random numbers. The standard distributions
// (std::uniform_real_distribution, std::normal_distribution) are implementation-defined across
// standard libraries, so the archive a seed produces would depend on the compiler; these helpers
// are written out on top of std::mt19937_64, whose output the standard pins. Sub-seeds are
// derived with SplitMix64 from (seed, stream, index), so every clip, motif and instance draws from
// its own stream and can be generated independently of the others.
// Thread-safety: a SynthRandom is used by one thread; the free functions are pure.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

namespace motif {

// SplitMix64's finaliser (Steele, Lea, Flood 2014): a bijective 64-bit mixer.
inline uint64_t SplitMix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// Named streams of sub-seeds: one per kind of object drawn.
enum class SeedStream : uint64_t {
  kClipLayout = 1,
  kMotifs = 2,
  kInstances = 3,
  kPlacement = 4,
  kClip = 5,
  kActivityLibrary = 6,
  kMotifTemplate = 7,
  kInstanceNoise = 8,
  kResequenceMotif = 9,
};

// The seed of item `index` of `stream` under the archive seed `seed`.
inline uint64_t DeriveSeed(uint64_t seed, SeedStream stream, uint64_t index) {
  return SplitMix64(SplitMix64(SplitMix64(seed) ^ static_cast<uint64_t>(stream)) + index);
}

class SynthRandom {
 public:
  explicit SynthRandom(uint64_t seed) : engine_(seed) {}

  uint64_t Next() { return engine_(); }
  // Uniform in [0, 1) from the 53 high bits.
  double Uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  // Uniform in [lo, hi).
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  // Uniform integer in [lo, hi] (inclusive), unbiased by rejection.
  uint64_t UniformInt(uint64_t lo, uint64_t hi) {
    const uint64_t span = hi - lo + 1;
    if (span == 0) return engine_();  // the full 64-bit range
    const uint64_t limit = UINT64_MAX - UINT64_MAX % span;
    uint64_t draw = engine_();
    while (draw >= limit) draw = engine_();
    return lo + draw % span;
  }
  // Standard normal by Box-Muller (one value per call: simple and reproducible).
  double Normal() {
    const double u1 = 1.0 - Uniform();  // (0, 1]
    const double u2 = Uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }
  double Normal(double mean, double sigma) { return mean + sigma * Normal(); }
  bool Bernoulli(double p) { return Uniform() < p; }

 private:
  std::mt19937_64 engine_;
};

}  // namespace motif
