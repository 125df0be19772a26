#pragma once
// The physics program without its transport: the world, what SIM_CONTROL does
// to it, the mode (speed, pause, sync), sync mode's horizons and which states
// go out. It knows nothing of LCM, reads no clock and names no other process:
// its shell (PhysicsShell) subscribes, calls the on_* methods (with the
// wall time where one matters) and publishes the Output each returns, in its
// order; its pacing (physics_pacing.hpp) decides when to step. The same shape
// as the other simulation cores (docs/design.md, "One shape for the cores").
#include <algorithm>
#include <chrono>
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
#include <vector>

#include "ubersim/logging.hpp"
#include "ubersim/physics/truth_demand.hpp"
#include "ubersim/physics/world.hpp"

namespace ubersim::physics {

struct CoreOptions {
  std::string scenario;  // for logs and acknowledgements
  double speed = 1.0;    // > 0 times real time, 0 as fast as possible, < 0 lockstep
  bool paused = false;
  double duration = 0;  // s of sim time after which the run ends, 0 = never
  bool sync = false;    // sync mode (docs/sync.md): step up to the horizon SIM_SYNC_HORIZON names
  // Sync mode with the automatic referee: also never past the state the referee
  // judges next (its REFEREE message names it, next_judge_time), so each
  // placement it decides on a state applies at the step from that state; that
  // state is the referee's demand. Physics holds while no referee speaks.
  bool sync_referee = false;
  // false (--truth-every-step): physics' own consumer wants every step's
  // state. Either way SIM_STATE goes out at the union of what the consumers
  // in the demand book want (docs/sync.md, "Ground truth on demand").
  bool truth_on_demand = true;
};

class PhysicsCore {
 public:
  using Clock = std::chrono::steady_clock;
  // Physics' own consumers in the demand book (TruthDemand), by name.
  static constexpr const char* kEveryStepConsumer = "physics: --truth-every-step";
  static constexpr const char* kNobodyAsksConsumer = "physics: while nobody asks";
  static constexpr const char* kRefereeConsumer = "physics: the referee's next state";
  static constexpr const char* kStepRequestConsumer = "physics: a STEP request";

  // What one call produced, to publish in this order. Returned by reference
  // to one the core reuses (valid until its next call), so that a state is
  // not copied every step: copying 22 robots costs more than encoding them.
  struct Output {
    std::vector<sim_state_t> states;           // SIM_STATE
    std::optional<field_geometry_t> geometry;  // SIM_GEOMETRY
    std::optional<sim_control_ack_t> ack;      // SIM_CONTROL_ACK
  };

  PhysicsCore(WorldSetup setup, CoreOptions options);

  void on_commands(const sim_commands_t& packet);
  // `dropped_input` is what the transport dropped, for the PING reply.
  const Output& on_control(const sim_control_t& request, const std::string& dropped_input);
  void on_sync_horizon(const sync_horizon_t& horizon);
  // Only with sync_referee: the referee has judged the state at its sim_time
  // and judges the one at its next_judge_time next.
  void on_referee(const referee_t& referee);
  void on_truth_demand(const truth_demand_t& demand, Clock::time_point wall);
  // The state at the step physics waits at, for a reader to acknowledge (as
  // fast as possible): nothing when it went out already, unless `again` (a
  // reader that started listening after it went out has not seen it).
  const Output& state_to_acknowledge(bool again);

  // One step; the state after it when one is due.
  const Output& step();
  // The state now (at start, and for late joiners while nothing moves).
  const Output& state();
  field_geometry_t geometry() const { return world_.geometry(); }
  // Forgets truth consumers not heard for 3 s (logged).
  void expire_demand(Clock::time_point wall);
  // In how many steps (1..max_steps) the next wanted state comes, max_steps if
  // none before. Steps nobody sees a state of need not run on time (the shell
  // sleeps until that step is due). 1 when every step's state goes out.
  std::int64_t steps_to_wanted_state(std::int64_t max_steps) const;

  // Nothing advances by itself: paused, or lockstep outside sync mode.
  bool idle() const { return paused_ || (!sync_ && lockstep()); }
  bool sync() const { return sync_; }
  bool paused() const { return paused_; }
  // The speed asked for: > 0 times real time, 0 as fast as possible, < 0 lockstep.
  double speed() const { return speed_; }
  bool lockstep() const { return speed_ < 0; }
  bool as_fast_as_possible() const { return speed_ == 0; }
  bool paced() const { return speed_ > 0; }
  // Changes whenever a wall-clock schedule must start again from the current
  // step (RESUME, RESET, STEP, SET_SPEED): the pacing re-anchors at its next
  // turn, at the wall time it is handed.
  std::uint64_t schedule_epoch() const { return schedule_epoch_; }
  // Sync mode: whether the step starting now may run: no command can still
  // come that applies at its start (docs/sync.md).
  bool below_horizon() const {
    return world_.time() + world_.dt() * 1e-6 < std::min(horizon_, referee_horizon_);
  }
  // Whether the step starting now stays short of the state the referee judges next.
  bool below_referee_horizon() const {
    return world_.time() + world_.dt() * 1e-6 < referee_horizon_;
  }
  // Sync mode: what holds physics at the horizon. The shell names it.
  struct HorizonBound {
    // Registration: the radio emulator's clients are still registering.
    enum class By { NoHorizonYet, Registration, Horizon, Referee };
    By by = By::NoHorizonYet;
    std::string waiting_for;  // By::Horizon: whom SIM_SYNC_HORIZON names
  };
  HorizonBound horizon_bound() const;
  bool duration_reached() const;
  // Sync mode: every frame published up to the current state has its answers
  // from every client (SIM_SYNC_HORIZON's answered_until), so a run may end here.
  bool last_frames_answered() const { return answered_until_ > world_.time() + world_.dt() * 1e-6; }
  double answered_until() const { return answered_until_; }

  World& world() { return world_; }
  const World& world() const { return world_; }
  ThrottledLog& warnings() { return log_; }
  std::int64_t steps() const { return steps_; }
  std::int64_t states_published() const { return states_published_; }
  std::int64_t controls_handled() const { return controls_handled_; }
  std::int64_t packets_received() const { return packets_received_; }
  std::uint64_t demand_late() const { return demand_.late(); }

 private:
  // Empties out_, keeping its states' memory in spare_ for the next ones.
  void clear_output();
  void step_once();
  void add_own_demand();
  void add_state();
  void acknowledge(const sim_control_t& request, bool ok, const std::string& message);
  // SIM_CONTROL actions with more to them than a line or two (on_control).
  void on_step_request(const sim_control_t& request);
  void on_speed_request(const sim_control_t& request);
  void on_define_robot_type(const sim_control_t& request);
  void on_set_field(const sim_control_t& request);

  World world_;
  CoreOptions options_;
  double speed_;
  std::uint64_t schedule_epoch_ = 0;
  bool paused_;
  Output out_;
  std::vector<sim_state_t> spare_;
  ThrottledLog log_;
  bool sync_ = false;
  TruthDemand demand_;
  double horizon_ = 0;         // s, from SIM_SYNC_HORIZON
  double answered_until_ = 0;  // s, from SIM_SYNC_HORIZON: frames published before it are answered
  double referee_horizon_;     // s, from REFEREE (+inf without --sync-referee)
  // Whether a SIM_SYNC_HORIZON came, and what its sender said it waits for.
  bool horizon_heard_ = false;
  std::int8_t horizon_held_by_ = sync_horizon_t::HELD_BY_NOTHING;
  std::string horizon_waiting_for_;
  double last_state_time_ = std::numeric_limits<double>::quiet_NaN();  // s, the last state out
  std::int64_t steps_ = 0;
  std::int64_t states_published_ = 0;
  std::int64_t controls_handled_ = 0;
  std::int64_t packets_received_ = 0;
};

}  // namespace ubersim::physics
