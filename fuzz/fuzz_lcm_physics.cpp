// Fuzz target: the physics server's LCM doors together with its handlers'
// validation (issue 13, item 3). Each input is one datagram on one of the
// channels physics subscribes to (physics_inputs.hpp), delivered through the
// real MessageBus (decode_bounded, the subscriptions ubersim_physics makes)
// into a real PhysicsShell and World (ODE) of the Division B scenario,
// which then steps 0.1 s. What must hold for every input:
//  * nothing crashes, leaks or allocates beyond the fuzz build's limits;
//  * every SIM_STATE physics publishes, during the input and after the
//    steps, is finite in every number (no NaN or infinity reaches the world),
//    and encodes.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>

#include "fuzz_support.hpp"
#include "physics_inputs.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/physics/physics_shell.hpp"
#include "ubersim/process_host.hpp"
#include "ubersim/topics.hpp"

namespace {

using ubersim::fuzz::PhysicsInput;

bool finite(const double* values, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) {
    if (!std::isfinite(values[i])) return false;
  }
  return true;
}

bool finite(const ubersim::body_state_t& body) {
  return finite(body.position, 3) && finite(body.orientation, 4) &&
         finite(body.linear_velocity, 3) && finite(body.angular_velocity, 3);
}

bool finite(const ubersim::sim_state_t& state) {
  if (!std::isfinite(state.sim_time) || !std::isfinite(state.dt) || !finite(state.ball)) {
    return false;
  }
  for (const ubersim::robot_state_t& robot : state.robots) {
    const double pose[] = {robot.x, robot.y, robot.orientation, robot.vx, robot.vy, robot.omega};
    if (!finite(pose, 6) || !finite(robot.body) ||
        !finite(robot.wheel_speeds.data(), robot.wheel_speeds.size())) {
      return false;
    }
  }
  return true;
}

std::string channel_name(PhysicsInput channel, const ubersim::ChannelNames& channels) {
  switch (channel) {
    case PhysicsInput::SimCommands:
      return ubersim::channel_name(channels, ubersim::topics::kSimCommands);
    case PhysicsInput::SimControl:
      return ubersim::channel_name(channels, ubersim::topics::kSimControl);
    case PhysicsInput::TruthDemand:
      return ubersim::channel_name(channels, ubersim::topics::kTruthDemand);
    case PhysicsInput::SyncHorizon:
      return ubersim::channel_name(channels, ubersim::topics::kSyncHorizon);
    case PhysicsInput::VisionSchedule:
      return ubersim::channel_name(channels, ubersim::topics::kVisionSchedule);
    case PhysicsInput::Referee:
    case PhysicsInput::Count:
      break;
  }
  return ubersim::channel_name(channels, ubersim::topics::kReferee);
}

const ubersim::physics::WorldSetup& division_b() {
  static const ubersim::physics::WorldSetup setup = [] {
    ubersim::physics::WorldSetup s =
        ubersim::physics::load_world_setup(UBERSIM_FUZZ_CONFIG_DIR, "division_b_6v6", "default");
    // The shipped limit (100,000 steps per STEP request) is valid input, but
    // at a few ms per step under the sanitizers one such input would take
    // minutes; the limit's own check runs the same with a lower value.
    s.physics.max_steps_per_request = 48;
    return s;
  }();
  return setup;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ubersim::fuzz::quiet_logging();
  division_b();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const auto channel = static_cast<PhysicsInput>((data[0] & ubersim::fuzz::kChannelMask) %
                                                 static_cast<int>(PhysicsInput::Count));
  // The host's bus (memq://) is the one ubersim_physics has on udpm://.
  ubersim::ProcessHost host("memq://", ubersim::ChannelNames(), "physics");
  ubersim::MessageBus& bus = host.bus();
  const ubersim::ChannelNames& channels = host.channels();
  ubersim::physics::ShellOptions options;
  options.scenario = "division_b_6v6";
  options.speed = -1;  // lockstep: it steps when told, whatever the wall clock does
  options.truth_on_demand = true;
  options.sync_referee = (data[0] & ubersim::fuzz::kSyncRefereeBit) != 0;
  options.sync = options.sync_referee || (data[0] & ubersim::fuzz::kSyncBit) != 0;
  ubersim::physics::PhysicsShell shell(division_b(), host, options);
  ubersim::subscribe(
      bus, channels, ubersim::topics::kSimState,
      [](const ubersim::sim_state_t& state) {
        if (!finite(state)) std::abort();
        ubersim::fuzz::encode_or_abort(state);
      },
      100000);

  bus.publish_encoded(channel_name(channel, channels), data + 1, size - 1);
  while (bus.handle_pending() > 0) {
  }
  ubersim::sim_control_t step{};
  step.sender = "fuzz";
  step.action = ubersim::sim_control_t::STEP;
  step.step_count = 24;
  ubersim::publish(bus, channels, ubersim::topics::kSimControl, step);
  while (bus.handle_pending() > 0) {
  }
  ubersim::sim_state_t state{};
  shell.world().fill_state(state);
  if (!finite(state)) std::abort();
  return 0;
}
