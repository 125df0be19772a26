#pragma once
// The physics server's figures: the core's counters and the loop's wall-clock
// ones (read by the benchmarks and logged at stop).
#include <cstdint>
#include <map>
#include <string>

namespace ubersim::physics {

struct ServerStats {
  std::int64_t steps = 0;
  std::int64_t states_published = 0;
  std::uint64_t demand_late = 0;  // demanded instants physics had passed when the demand came
  std::int64_t controls_handled = 0;
  std::int64_t packets_received = 0;
  std::int64_t schedule_restarts = 0;  // times real time could not be kept
  double wall_seconds = 0;
  double drift = 0;  // s, sim time ahead of the real-time schedule at the end (paced modes)
  // Sync mode: wall time spent waiting at the horizon, by what bounded it
  // (a client's name, "vision", the sync clients' registration), and how many waits.
  std::map<std::string, double> sync_wait_seconds;
  std::map<std::string, std::int64_t> sync_waits;
  // Sync mode and --wait-for-vision: wall time from the first state to the
  // end (the start, waiting for the emulators and clients to be ready, left out).
  double sync_run_seconds = 0;
  // As fast as possible: wall time spent waiting for the vision emulator to
  // catch up (docs/vision.md, "As fast as possible"), how many waits, the
  // states sent only for it to acknowledge, and how often it fell silent.
  double vision_wait_seconds = 0;
  std::int64_t vision_waits = 0;
  std::int64_t states_for_vision = 0;
  std::int64_t vision_silences = 0;
};

}  // namespace ubersim::physics
