// Fuzz target: the vision and radio emulators' LCM inputs together with
// their handlers' validation (issue 13, item 3). Each input is one datagram
// on one channel (emulator_inputs.hpp). It is decoded as the processes decode
// it (decode_bounded) and given to the real cores (VisionEmulator and
// RadioEmulator with the cmdragons02 profiles), between a real state of the
// Division B scenario before it and 0.2 s of real states after it, so that
// frames are captured and released and commands go through the links. What
// must hold for every input:
//  * nothing crashes, leaks or allocates beyond the fuzz build's limits;
//  * every VISION frame, SIM_COMMANDS and RADIO_FEEDBACK the cores return is
//    finite in every number and encodes (bad input is dropped, never passed on).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <ubersim/emulator_realism_t.hpp>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/vision_cameras_t.hpp>
#include <vector>

#include "emulator_inputs.hpp"
#include "fuzz_support.hpp"
#include "ubersim/bounded_decode.hpp"
#include "ubersim/physics/world.hpp"
#include "ubersim/radio/radio_emulator.hpp"
#include "ubersim/radio/radio_profile.hpp"
#include "ubersim/vision/robot_sizes.hpp"
#include "ubersim/vision/vision_emulator.hpp"
#include "ubersim/vision/vision_profile.hpp"

namespace {

using ubersim::fuzz::EmulatorInput;

bool finite(double value) {
  return std::isfinite(value);
}

void check(const ubersim::vision_frame_t& frame) {
  bool ok = finite(frame.t_capture) && finite(frame.t_sent);
  for (const auto& ball : frame.balls) {
    ok = ok && finite(ball.confidence) && finite(ball.x) && finite(ball.y) &&
         finite(ball.pixel_x) && finite(ball.pixel_y) && finite(ball.area) && ball.area >= 0;
  }
  for (const auto* robots : {&frame.robots_yellow, &frame.robots_blue}) {
    for (const auto& robot : *robots) {
      ok = ok && finite(robot.confidence) && finite(robot.x) && finite(robot.y) &&
           finite(robot.orientation) && finite(robot.pixel_x) && finite(robot.pixel_y);
    }
  }
  if (!ok) std::abort();
  ubersim::fuzz::encode_or_abort(frame);
}

void check(const ubersim::radio::RadioEmulator::Output& out) {
  for (const ubersim::sim_commands_t& message : out.commands) {
    bool ok =
        finite(message.t_received) && finite(message.t_apply) && finite(message.command_timeout);
    for (const ubersim::robot_command_t& c : message.commands) {
      ok = ok && finite(c.vx) && finite(c.vy) && finite(c.omega) && finite(c.kick_speed) &&
           finite(c.chip_speed) && finite(c.chip_angle) && finite(c.dribbler_speed);
      for (double w : c.wheel_speeds) ok = ok && finite(w);
    }
    if (!ok) std::abort();
    ubersim::fuzz::encode_or_abort(message);
  }
  for (const auto& [team, feedback] : out.feedback) {
    if (!finite(feedback.t_measured) || !finite(feedback.t_sent)) std::abort();
    ubersim::fuzz::encode_or_abort(feedback);
  }
}

struct Fixture {
  ubersim::vision::VisionProfile vision_profile;
  ubersim::vision::RobotSizes robot_sizes;
  ubersim::radio::RadioProfile radio_profile;
  ubersim::field_geometry_t field{};
  std::vector<ubersim::sim_state_t> states;  // 0.2 s of Division B, every step

  Fixture()
      : vision_profile(
            ubersim::vision::load_vision_profile(UBERSIM_FUZZ_CONFIG_DIR, "cmdragons02")),
        robot_sizes(ubersim::vision::RobotSizes::from_config_dir(UBERSIM_FUZZ_CONFIG_DIR)),
        radio_profile(ubersim::radio::load_radio_profile(UBERSIM_FUZZ_CONFIG_DIR, "cmdragons02")) {
    ubersim::physics::World world(
        ubersim::physics::load_world_setup(UBERSIM_FUZZ_CONFIG_DIR, "division_b_6v6", "default"));
    field = world.geometry();
    for (int i = 0; i <= 48; ++i) {
      ubersim::sim_state_t state{};
      world.fill_state(state);
      states.push_back(std::move(state));
      world.step();
    }
  }
};

const Fixture& fixture() {
  static const Fixture instance;
  return instance;
}

template <class Msg>
bool decode(const std::uint8_t* data, std::size_t size, Msg& out) {
  return ubersim::decode_bounded(data, size, out);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ubersim::fuzz::quiet_logging();
  fixture();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const Fixture& f = fixture();
  const auto [channel, bytes, length] = ubersim::fuzz::channel_input<EmulatorInput>(data, size);

  ubersim::vision::VisionEmulator vision(f.vision_profile, f.robot_sizes);
  ubersim::radio::RadioEmulator radio({f.radio_profile, f.radio_profile}, std::nullopt);
  vision.on_field_geometry(f.field);
  const auto feed = [&](const ubersim::sim_state_t& state) {
    for (const auto& frame : vision.on_sim_state(state).frames) check(frame);
    check(radio.on_sim_state(state, {}));
  };
  feed(f.states.front());

  switch (channel) {
    case EmulatorInput::RadioYellow:
    case EmulatorInput::RadioBlue: {
      ubersim::radio_packet_t packet;
      if (decode(bytes, length, packet)) {
        const auto team =
            channel == EmulatorInput::RadioYellow ? ubersim::Team::Yellow : ubersim::Team::Blue;
        check(radio.on_radio_packet(team, packet, {}));
      }
      break;
    }
    case EmulatorInput::SimState: {
      ubersim::sim_state_t state;
      if (decode(bytes, length, state)) feed(state);
      break;
    }
    case EmulatorInput::SimGeometry: {
      ubersim::field_geometry_t geometry;
      if (decode(bytes, length, geometry)) vision.on_field_geometry(geometry);
      break;
    }
    case EmulatorInput::VisionCameras: {
      ubersim::vision_cameras_t cameras;
      if (decode(bytes, length, cameras)) vision.apply_cameras(cameras);
      (void)vision.geometry_message();
      break;
    }
    case EmulatorInput::EmulatorRealism:
    case EmulatorInput::Count: {
      ubersim::emulator_realism_t realism;
      if (decode(bytes, length, realism)) {
        vision.apply_realism(realism);
        radio.apply_realism(realism);
      }
      break;
    }
  }
  for (std::size_t i = 1; i < f.states.size(); ++i) feed(f.states[i]);
  (void)vision.truth_demand();
  (void)radio.truth_demand();
  return 0;
}
