#pragma once
// The physics shell: a PhysicsCore (physics_core.hpp) on the process host
// (process_host.hpp), with the pacing policies that step it
// (physics_pacing.hpp): what the host is given.
//
//   subscribes SIM_COMMANDS (sim_commands_t): held until t_apply, then applied (unhurried)
//              SIM_CONTROL  (sim_control_t):  place, setup, pause, resume, reset,
//                                             step, speed, sync, seed, geometry, ping
//              SIM_SYNC_HORIZON (sync_horizon_t): in sync mode, how far it may step
//              SIM_TRUTH_DEMAND (truth_demand_t): which states its readers want
//              SIM_VISION_SCHEDULE (vision_schedule_t): the vision listens, and how far it got
//              REFEREE (referee_t): with --sync-referee, the state it judges next
//   publishes  SIM_STATE    (sim_state_t):    at the steps its demand book wants
//                                             (TruthDemand: SIM_TRUTH_DEMAND's and its own)
//              SIM_GEOMETRY (field_geometry_t): at start, every GEOMETRY_PUBLISH_PERIOD
//                                             of wall time (a host timer), and on request
//              SIM_CONTROL_ACK (sim_control_ack_t): one per SIM_CONTROL
//   timers     the geometry (and, while idle, the state for late joiners); the
//              expiry of truth consumers not heard for 3 s
//   at stop    the run's summary (the lines tools/launch.sh and the benches read)
#include <optional>

#include "ubersim/physics/output_publisher.hpp"
#include "ubersim/physics/physics_core.hpp"
#include "ubersim/physics/physics_pacing.hpp"
#include "ubersim/physics/server_stats.hpp"
#include "ubersim/physics/stepping_clock.hpp"
#include "ubersim/process_host.hpp"

namespace ubersim::physics {

struct ShellOptions : CoreOptions {
  // Outside sync mode: publish no state and take no step until a vision
  // emulator listens (its SIM_VISION_SCHEDULE), as sync mode does, so that it
  // sees the run from sim time 0 (tools/launch.sh --speed 0 passes it).
  bool wait_for_vision = false;
};

class PhysicsShell {
 public:
  // Subscribes on the host's bus; the host must outlive the shell.
  PhysicsShell(WorldSetup setup, ProcessHost& host, ShellOptions options);
  PhysicsShell(const PhysicsShell&) = delete;
  PhysicsShell& operator=(const PhysicsShell&) = delete;

  // Runs on the host until a signal, host.stop() or the duration. Returns the
  // exit code. Once per shell.
  int run();

  World& world() { return core_.world(); }
  // The core's counters with the loop's wall-clock figures.
  ServerStats stats() const;

 private:
  void subscribe();
  // The geometry repeat and the truth-demand expiry, on the host's timers.
  void add_timers();
  void log_start() const;
  // The summary at stop (tools/launch.sh and the benches read its lines).
  void log_stop(Pacing::Clock::time_point start);
  void log_waits() const;

  ProcessHost& host_;
  ShellOptions options_;
  PhysicsCore core_;
  OutputPublisher publisher_;
  ServerStats stats_;             // the loop's own figures (wall clock, waits)
  SteppingClock stepping_clock_;  // CPU time of the steps in real time
  PhysicsPacing pacing_;
};

}  // namespace ubersim::physics
