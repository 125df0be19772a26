#pragma once
// Seeded random numbers that are the same on every platform and standard
// library: std::mt19937_64's output is fixed by the standard, but the
// distributions (std::normal_distribution ...) are not, so uniform and
// Gaussian draws are made here from the raw engine output.
#include <cmath>
#include <cstdint>
#include <random>

namespace ubersim::vision {

// SplitMix64 step: turns (seed, stream) into well-mixed, independent engine seeds.
inline std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (stream + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

class RandomSource {
 public:
  RandomSource(std::uint64_t seed, std::uint64_t stream) : engine_(mix_seed(seed, stream)) {}

  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

  bool chance(double probability) { return uniform() < probability; }

  // Standard normal by the Box-Muller transform (one value per call; the
  // second is discarded so the draw count per call is fixed).
  double gaussian() {
    const double u1 = 1.0 - uniform();  // (0, 1]: log stays finite
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }
  double gaussian(double sigma) { return sigma > 0 ? sigma * gaussian() : 0.0; }

 private:
  std::mt19937_64 engine_;
};

}  // namespace ubersim::vision
