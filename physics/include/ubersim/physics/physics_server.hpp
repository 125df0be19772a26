#pragma once
// The physics server: the world plus messages and pacing.
//
//   subscribes SIM_COMMANDS (sim_commands_t): held until t_apply, then applied
//              SIM_CONTROL  (sim_control_t):  place, setup, pause, resume, reset,
//                                             step, speed, sync, seed, geometry, ping
//              SIM_SYNC_HORIZON (sync_horizon_t): in sync mode, how far it may step
//   publishes  SIM_STATE    (sim_state_t):    after every step (or at STATE_PUBLISH_RATE)
//              SIM_GEOMETRY (field_geometry_t): at start, every GEOMETRY_PUBLISH_PERIOD
//                                             of wall time, and on request
//              SIM_CONTROL_ACK (sim_control_ack_t): one per SIM_CONTROL
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/sync_horizon_t.hpp>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/physics/pacer.hpp"
#include "ubersim/physics/truth_demand.hpp"
#include "ubersim/physics/world.hpp"

namespace ubersim {
class ShutdownSignal;
}

namespace ubersim::physics {

struct ServerOptions {
  std::string scenario;  // for logs and acknowledgements
  double speed = 1.0;    // > 0 times real time, 0 as fast as possible, < 0 lockstep
  bool paused = false;
  double duration = 0;  // s of sim time after which run() returns, 0 = never
  bool sync = false;    // sync mode (docs/sync.md): step up to the radio emulator's horizon
  // Sync mode with the automatic referee: also never past the state the referee
  // judged last (its REFEREE message carries that state's sim time), so each
  // placement it sends applies at the step after that state; SIM_STATE then
  // goes out after every step. Physics holds while no referee speaks.
  bool sync_referee = false;
  // SIM_STATE only at the instants consumers ask for on SIM_TRUTH_DEMAND
  // (every step while nobody has asked): docs/sync.md, "Ground truth on demand".
  bool truth_on_demand = false;
};

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
  // Sync mode: wall time from the first state to the end (the start, waiting
  // for the emulators and clients to be ready, left out).
  double sync_run_seconds = 0;
};

class PhysicsServer {
 public:
  PhysicsServer(WorldSetup setup, MessageBus& bus, const ChannelNames& channels,
                ServerOptions options);

  // Runs until the shutdown signal (if any) or the duration. Returns the exit code.
  int run(const ShutdownSignal* shutdown);

  World& world() { return world_; }
  const ServerStats& stats() const { return stats_; }

 private:
  void on_control(const sim_control_t& request);
  void acknowledge(const sim_control_t& request, bool ok, const std::string& message);
  void step_and_publish(bool publish_every_step);
  void publish_state();
  void publish_geometry();
  bool idle() const { return paused_ || (!sync_ && pacer_.lockstep()); }
  // Sync mode: whether the step starting now may run: no command can still
  // come that applies at its start (docs/sync.md).
  bool below_horizon() const {
    return world_.time() + world_.dt() * 1e-6 < std::min(horizon_, referee_horizon_);
  }
  void wait_at_horizon(const ShutdownSignal* shutdown);
  void log_sync_waits() const;
  // Waits until `deadline` or a message or a signal; handles messages.
  void wait_until(Pacer::Clock::time_point deadline, const ShutdownSignal* shutdown);
  bool duration_reached() const;
  double first_state_time() const;

  World world_;
  MessageBus& bus_;
  std::string state_channel_;
  std::string geometry_channel_;
  std::string ack_channel_;
  ServerOptions options_;
  Pacer pacer_;
  bool paused_;
  double next_state_time_ = 0;  // sim time of the next publication (STATE_PUBLISH_RATE > 0)
  sim_state_t state_{};
  std::vector<uint8_t> state_buffer_;  // encoded SIM_STATE, reused every step
  ServerStats stats_;
  ThrottledLog log_;
  bool sync_ = false;
  TruthDemand demand_;
  double horizon_ = 0;      // s, from SIM_SYNC_HORIZON
  double referee_horizon_;  // s, from REFEREE (+inf without --sync-referee)
  std::string horizon_bound_ = "the radio emulator (no SIM_SYNC_HORIZON yet)";
  // Sync mode publishes its first state only once the vision emulator listens
  // and the radio emulator has every client it expects (both have spoken), so
  // that every run starts alike.
  bool vision_heard_ = false;
  bool radio_ready_ = false;
  bool first_state_sent_ = false;
  Pacer::Clock::time_point first_state_wall_{};
};

}  // namespace ubersim::physics
