#pragma once
// The physics server: a PhysicsCore (physics_core.hpp) on the bus, and the
// loop that paces it and waits for messages.
//
//   subscribes SIM_COMMANDS (sim_commands_t): held until t_apply, then applied
//              SIM_CONTROL  (sim_control_t):  place, setup, pause, resume, reset,
//                                             step, speed, sync, seed, geometry, ping
//              SIM_SYNC_HORIZON (sync_horizon_t): in sync mode, how far it may step
//   publishes  SIM_STATE    (sim_state_t):    at the steps SIM_TRUTH_DEMAND asks for (every
//                                             step while nobody asks, or at STATE_PUBLISH_RATE)
//              SIM_GEOMETRY (field_geometry_t): at start, every GEOMETRY_PUBLISH_PERIOD
//                                             of wall time, and on request
//              SIM_CONTROL_ACK (sim_control_ack_t): one per SIM_CONTROL
#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/physics/physics_core.hpp"
#include "ubersim/physics/stepping_clock.hpp"

namespace ubersim {
class ShutdownSignal;
}

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
  // (a client's name, "vision", "registration"), and how many waits.
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

class PhysicsServer {
 public:
  PhysicsServer(WorldSetup setup, MessageBus& bus, const ChannelNames& channels,
                ServerOptions options);

  // Runs until the shutdown signal (if any) or the duration. Returns the exit code.
  int run(const ShutdownSignal* shutdown);

  World& world() { return core_.world(); }
  // The core's counters with the loop's wall-clock figures.
  ServerStats stats() const;

 private:
  void publish(const PhysicsCore::Output& out);
  void publish_geometry();
  void wait_at_horizon(const ShutdownSignal* shutdown);
  // As fast as possible: one wait for the vision emulator's acknowledgement.
  void wait_for_vision(const ShutdownSignal* shutdown);
  // Sync mode, duration reached: until the last frames' answers are in (at most 3 s).
  void wait_for_last_answers(const ShutdownSignal* shutdown);
  // Paced: when to wake for the step that is due at `due`. With states on
  // demand, the steps before the next wanted state run when that one is due
  // (docs/sync.md, "Steps nobody sees"), instead of one wakeup a step.
  Pacer::Clock::time_point wake_for(Pacer::Clock::time_point due) const;
  void log_sync_waits() const;
  // Waits until `deadline` or a message or a signal; handles messages.
  void wait_until(Pacer::Clock::time_point deadline, const ShutdownSignal* shutdown);

  PhysicsCore core_;
  MessageBus& bus_;
  std::string state_channel_;
  std::string geometry_channel_;
  std::string ack_channel_;
  ServerOptions options_;
  std::vector<uint8_t> state_buffer_;  // encoded SIM_STATE, reused every step
  ServerStats stats_;                  // the loop's own figures (wall clock, sync waits)
  SteppingClock stepping_clock_;       // CPU time of the steps in real time
  // SIM_VISION_SCHEDULE wakes physics (sync mode, or started as fast as possible).
  bool schedule_wakes_;
  bool first_state_sent_ = false;
  // When physics began to wait for the vision at the current step.
  std::optional<Pacer::Clock::time_point> vision_wait_began_;
  Pacer::Clock::time_point first_state_wall_{};
};

}  // namespace ubersim::physics
