#pragma once
// One simulated world in the calling process, for the Python module: the
// cores of the programs (the physics process's PhysicsCore in sync mode, the
// vision and radio emulators), wired together without LCM and driven by the
// caller's steps as the sync driver drives the processes (docs/python.md).
// Commands are checked by the radio emulator's validator, the one every part
// shares. Everything runs in sim time: nothing here reads a clock, so the same
// seed and the same calls give the same results, bit for bit, on any thread.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/radio_feedback_t.hpp>
#include <ubersim/robot_command_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/vision_frame_t.hpp>
#include <utility>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/physics/physics_core.hpp"
#include "ubersim/physics/world.hpp"
#include "ubersim/radio/radio_emulator.hpp"
#include "ubersim/referee/situations.hpp"
#include "ubersim/vision/vision_emulator.hpp"

namespace ubersim::python {

struct SimOptions {
  std::string config_dir;  // "" = the default config folder (UBERSIM_CONFIG_DIR, else the build's)
  std::string scenario = "division_b_6v6";
  std::string field;  // "" = the scenario's field
  std::string physics = "default";
  std::string vision_profile;  // "" = no vision emulation
  std::string radio_profile;   // "" = commands reach the robots at once, none lost
  std::uint64_t seed = 0;      // physics solver, vision noise and radio loss
  double step = 0.025;         // s of sim time per step()
};

// One robot's command for this step (a row of the commands array).
struct RobotOrder {
  Team team = Team::Yellow;
  int id = 0;
  robot_command_t command{};
};

// What one step produced. Reused from step to step (valid until the next call).
struct StepOutput {
  sim_state_t truth;                                        // after the step
  std::vector<vision_frame_t> frames;                       // published during the step
  std::vector<std::pair<Team, radio_feedback_t>> feedback;  // delivered during the step
};

class InProcessSim {
 public:
  // Throws ConfigError (bad names, bad files) or std::invalid_argument.
  explicit InProcessSim(SimOptions options);

  // Back to the scenario at sim time 0, vision and radio afresh; a new seed
  // when given (else the one in use).
  void reset(std::optional<std::uint64_t> seed = std::nullopt);
  // SETUP (every robot removed first) or PLACE; throws std::invalid_argument
  // with physics' reason when refused (nothing changes then).
  void place(const sim_control_t& request, bool setup);
  // A referee situation (kick-off, free kick, ...): robots and ball placed by
  // the SSL rules' distances, everyone stopped. Throws std::invalid_argument.
  void situation(const referee::SituationRequest& request, referee::FieldSides sides);

  // Throws std::invalid_argument, changing nothing, when the radio
  // emulator's validator (without the profile's sanity limits) finds an order
  // wrong: a robot not on the field or commanded twice, a non-finite value, an
  // unknown mode, a wheel count that is not the robot's.
  void check_orders(const std::vector<RobotOrder>& orders) const;
  // Sends the orders (through the radio when emulated), then steps physics
  // until the next step boundary. Call check_orders first: step() assumes it.
  const StepOutput& step(const std::vector<RobotOrder>& orders);

  // How many wheels that robot has; nothing when it is not on the field.
  std::optional<std::size_t> wheel_count(Team team, int id) const;

  const sim_state_t& truth();                             // the state now
  const StepOutput& last_output() const { return out_; }  // what the last step() returned
  field_geometry_t geometry() const { return core_->geometry(); }
  const physics::World& world() const { return core_->world(); }
  const SimOptions& options() const { return options_; }
  std::uint64_t seed() const { return options_.seed; }
  double time() const { return core_->world().time(); }
  bool vision_emulated() const { return vision_ != nullptr; }
  bool radio_emulated() const { return radio_ != nullptr; }
  const vision::VisionEmulator* vision() const { return vision_.get(); }
  const radio::RadioEmulator* radio() const { return radio_.get(); }
  // The robot type new robots get when a placement names none.
  const std::string& default_robot_type() const { return default_robot_type_; }

 private:
  void start_emulators();
  // A SIM_CONTROL request to the core; throws std::invalid_argument when refused.
  void control(const sim_control_t& request);
  void send(const std::vector<RobotOrder>& orders);
  // Sync mode's horizon: the caller's next commands come at `end` at the earliest.
  void release_until(double end);
  void feed_emulators(const std::vector<sim_state_t>& states);

  SimOptions options_;
  std::string config_dir_;
  std::string default_robot_type_;
  std::unique_ptr<physics::PhysicsCore> core_;
  std::unique_ptr<vision::VisionEmulator> vision_;
  std::unique_ptr<radio::RadioEmulator> radio_;
  std::int64_t steps_taken_ = 0;  // step() calls since the last reset
  std::int64_t packet_sequence_ = 0;
  StepOutput out_;
};

}  // namespace ubersim::python
