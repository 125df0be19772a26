#pragma once
// The physics server without its transport: the world, what SIM_CONTROL does
// to it, the pacing schedule, sync mode's horizons and which states go out.
// It knows nothing of LCM: the server (physics_server.hpp) subscribes, calls
// the on_* methods and publishes the Output each returns, in its order. The
// same shape as the radio and vision emulator cores (docs/design.md, "One
// shape for the cores").
#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/referee_t.hpp>
#include <ubersim/sim_commands_t.hpp>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/sync_horizon_t.hpp>
#include <ubersim/truth_demand_t.hpp>
#include <ubersim/vision_schedule_t.hpp>
#include <vector>

#include "ubersim/logging.hpp"
#include "ubersim/physics/pacer.hpp"
#include "ubersim/physics/truth_demand.hpp"
#include "ubersim/physics/world.hpp"

namespace ubersim::physics {

struct ServerOptions {
  std::string scenario;  // for logs and acknowledgements
  double speed = 1.0;    // > 0 times real time, 0 as fast as possible, < 0 lockstep
  bool paused = false;
  double duration = 0;  // s of sim time after which run() returns, 0 = never
  bool sync = false;    // sync mode (docs/sync.md): step up to the radio emulator's horizon
  // Sync mode with the automatic referee: also never past the state the referee
  // judges next (its REFEREE message names it, next_judge_time), so each
  // placement it decides on a state applies at the step from that state.
  // SIM_STATE goes out after every step, or with truth_on_demand at the
  // demanded steps and that state. Physics holds while no referee speaks.
  bool sync_referee = false;
  // SIM_STATE only at the instants consumers ask for on SIM_TRUTH_DEMAND
  // (every step while nobody has asked): docs/sync.md, "Ground truth on demand".
  // The default; --truth-every-step turns it off.
  bool truth_on_demand = true;
  // Outside sync mode: publish no state and take no step until a vision
  // emulator listens (its SIM_VISION_SCHEDULE), as sync mode does, so that it
  // sees the run from sim time 0 (tools/launch.sh --speed 0 passes it).
  bool wait_for_vision = false;
};

class PhysicsCore {
 public:
  using Clock = Pacer::Clock;

  // What one call produced, to publish in this order. Returned by reference
  // to one the core reuses (valid until its next call), so that a state is
  // not copied every step: copying 22 robots costs more than encoding them.
  struct Output {
    std::vector<sim_state_t> states;           // SIM_STATE
    std::optional<field_geometry_t> geometry;  // SIM_GEOMETRY
    std::optional<sim_control_ack_t> ack;      // SIM_CONTROL_ACK
  };

  PhysicsCore(WorldSetup setup, ServerOptions options);

  void on_commands(const sim_commands_t& packet);
  // `dropped_input` is what the transport dropped, for the PING reply.
  const Output& on_control(const sim_control_t& request, const std::string& dropped_input);
  void on_sync_horizon(const sync_horizon_t& horizon);
  // Only with sync_referee: the referee has judged the state at its sim_time
  // and judges the one at its next_judge_time next.
  void on_referee(const referee_t& referee);
  void on_truth_demand(const truth_demand_t& demand, Clock::time_point wall);
  // The vision emulator listens; as fast as possible, its t_state says how
  // far it has got (docs/vision.md, "As fast as possible").
  void on_vision_schedule(const vision_schedule_t& schedule, Clock::time_point wall);
  // As fast as possible outside sync mode: whether the next step must wait
  // because physics is kVisionLead ahead of the last state the vision
  // acknowledged. False while no vision is heard, or one fell silent for
  // kVisionSilence (logged once per silence).
  bool waits_for_vision(Clock::time_point wall);
  // The state at the step physics waits at, for the vision to acknowledge:
  // nothing when it went out already, unless `again` (a vision that started
  // listening after it went out has not seen it).
  const Output& state_for_vision(bool again);

  // One step; the state after it when one is due.
  const Output& step();
  // The state now (at start, and for late joiners while nothing moves).
  const Output& state();
  field_geometry_t geometry() const { return world_.geometry(); }
  // Forgets truth consumers not heard for 3 s (logged).
  void expire_demand(Clock::time_point wall);
  // States on demand with someone asking: in how many steps (1..max_steps) the
  // next wanted state comes, max_steps if none before. Steps nobody sees a
  // state of need not run on time (the server sleeps until that step is due).
  // 1 when every step's state goes out.
  std::int64_t steps_to_wanted_state(std::int64_t max_steps) const;

  // Nothing advances by itself: paused, or lockstep outside sync mode.
  bool idle() const { return paused_ || (!sync_ && pacer_.lockstep()); }
  bool sync() const { return sync_; }
  bool paused() const { return paused_; }
  // Sync mode: whether the step starting now may run: no command can still
  // come that applies at its start (docs/sync.md).
  bool below_horizon() const {
    return world_.time() + world_.dt() * 1e-6 < std::min(horizon_, referee_horizon_);
  }
  // Whether the step starting now stays short of the state the referee judges next.
  bool below_referee_horizon() const {
    return world_.time() + world_.dt() * 1e-6 < referee_horizon_;
  }
  // Sync mode: what holds physics at the horizon (a client's name, "vision", "referee" ...).
  std::string horizon_bound() const;
  // Sync mode publishes its first state only once the vision emulator listens
  // and the radio emulator has every client it expects (both have spoken), so
  // that every run starts alike.
  // Outside sync mode with wait_for_vision: once the vision emulator listens.
  bool ready_to_start() const { return vision_heard_ && (radio_ready_ || !sync_); }
  bool duration_reached() const;
  // Sync mode: every frame published up to the current state has its answers
  // from every client (the radio emulator says so), so a run may end here.
  bool last_frames_answered() const { return answered_until_ > world_.time() + world_.dt() * 1e-6; }
  double answered_until() const { return answered_until_; }

  World& world() { return world_; }
  const World& world() const { return world_; }
  Pacer& pacer() { return pacer_; }
  const Pacer& pacer() const { return pacer_; }
  ThrottledLog& warnings() { return log_; }
  std::int64_t steps() const { return steps_; }
  std::int64_t states_published() const { return states_published_; }
  std::int64_t controls_handled() const { return controls_handled_; }
  std::int64_t packets_received() const { return packets_received_; }
  std::uint64_t demand_late() const { return demand_.late(); }
  // Times the vision emulator fell silent while physics was waiting for it.
  std::int64_t vision_silences() const { return vision_silences_; }
  // Paced modes: CPU time of this thread spent in World::step (s), so that
  // the cost of everything else (messages, waiting) can be told from stepping.

 private:
  // Empties out_, keeping its states' memory in spare_ for the next ones.
  void clear_output();
  void step_once(bool publish_every_step);
  void add_state();
  void acknowledge(const sim_control_t& request, bool ok, const std::string& message);
  // SIM_CONTROL actions with more to them than a line or two (on_control).
  void on_step_request(const sim_control_t& request);
  void on_speed_request(const sim_control_t& request, Clock::time_point now);
  void on_define_robot_type(const sim_control_t& request);
  void on_set_field(const sim_control_t& request);
  double first_state_time() const;

  World world_;
  ServerOptions options_;
  Pacer pacer_;
  bool paused_;
  double next_state_time_ = 0;  // sim time of the next publication (STATE_PUBLISH_RATE > 0)
  Output out_;
  std::vector<sim_state_t> spare_;
  ThrottledLog log_;
  bool sync_ = false;
  TruthDemand demand_;
  double horizon_ = 0;         // s, from SIM_SYNC_HORIZON
  double answered_until_ = 0;  // s, from SIM_SYNC_HORIZON: frames published before it are answered
  double referee_horizon_;     // s, from REFEREE (+inf without --sync-referee)
  std::string horizon_bound_ = "the radio emulator (no SIM_SYNC_HORIZON yet)";
  bool vision_heard_ = false;
  // The vision emulator's progress: the sim time of the last state it
  // acknowledged (-inf while it has seen none), and when it last spoke.
  double vision_time_ = -std::numeric_limits<double>::infinity();
  Clock::time_point vision_wall_{};
  bool vision_silent_ = false;
  std::int64_t vision_silences_ = 0;
  double last_state_time_ = std::numeric_limits<double>::quiet_NaN();  // s, the last state out
  bool radio_ready_ = false;
  std::int64_t steps_ = 0;
  std::int64_t states_published_ = 0;
  std::int64_t controls_handled_ = 0;
  std::int64_t packets_received_ = 0;
};

}  // namespace ubersim::physics
