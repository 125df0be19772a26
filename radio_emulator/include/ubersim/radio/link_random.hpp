#pragma once
// The random draws of one direction of one team's link. Seeded per (seed,
// team, direction), so each stream is reproducible and independent of the
// other team's traffic: same seed and same inputs give the same output.
#include <algorithm>
#include <cstdint>
#include <random>

#include "ubersim/channels.hpp"
#include "ubersim/radio/radio_profile.hpp"

namespace ubersim::radio {

enum class Direction : std::uint32_t { Command = 0, Feedback = 1 };

class LinkRandom {
 public:
  LinkRandom(std::uint64_t seed, Team team, Direction direction) {
    std::seed_seq sequence{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                           static_cast<std::uint32_t>(team), static_cast<std::uint32_t>(direction)};
    engine_.seed(sequence);
  }

  bool happens(double probability) {
    if (probability <= 0) return false;
    return uniform_(engine_) < probability;
  }

  // latency + Gaussian jitter, never below zero (a packet cannot arrive before it was sent).
  double delay(const LinkTiming& timing) {
    if (timing.latency_jitter <= 0) return timing.latency;
    std::normal_distribution<double> jitter(0.0, timing.latency_jitter);
    return std::max(0.0, timing.latency + jitter(engine_));
  }

 private:
  std::mt19937_64 engine_;
  std::uniform_real_distribution<double> uniform_{0.0, 1.0};
};

}  // namespace ubersim::radio
