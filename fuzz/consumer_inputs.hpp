#pragma once
// The input of fuzz_lcm_consumers: one byte that picks the channel, then the
// datagram as it arrives on it; and the real traffic of a Division B game the
// target plays around it and the seed writer draws its seeds from.
#include <cstdint>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/vision_frame_t.hpp>
#include <ubersim/vision_geometry_t.hpp>
#include <utility>
#include <vector>

#include "ubersim/physics/world.hpp"
#include "ubersim/vision/robot_sizes.hpp"
#include "ubersim/vision/vision_emulator.hpp"
#include "ubersim/vision/vision_profile.hpp"

namespace ubersim::fuzz {

// The channels the referee (auto), the viewer and the SSL bridge read.
enum class ConsumerInput : std::uint8_t {
  SimState,        // sim_state_t -> referee, viewer, bridge (tracked frames)
  SimGeometry,     // field_geometry_t -> referee (the field it judges on), viewer
  Vision,          // vision_frame_t -> viewer, bridge (detection packets)
  VisionGeometry,  // vision_geometry_t -> viewer, bridge (geometry packets)
  RadioYellow,     // radio_packet_t -> viewer
  RadioBlue,       // radio_packet_t -> viewer
  SimControlAck,   // sim_control_ack_t -> viewer
  Referee,         // referee_t -> bridge (SSL game controller packets), viewer
  Count
};

// 0.2 s of the Division B scenario as physics and the vision emulator
// (cmdragons02) publish it.
struct ConsumerTraffic {
  field_geometry_t field{};
  vision_geometry_t vision_geometry{};
  std::vector<sim_state_t> states;     // every step
  std::vector<vision_frame_t> frames;  // every frame released meanwhile
};

inline ConsumerTraffic division_b_traffic() {
  ConsumerTraffic traffic;
  physics::World world(
      physics::load_world_setup(UBERSIM_FUZZ_CONFIG_DIR, "division_b_6v6", "default"));
  vision::VisionEmulator vision(vision::load_vision_profile(UBERSIM_FUZZ_CONFIG_DIR, "cmdragons02"),
                                vision::RobotSizes::from_config_dir(UBERSIM_FUZZ_CONFIG_DIR));
  traffic.field = world.geometry();
  vision.on_field_geometry(traffic.field);
  traffic.vision_geometry = vision.geometry_message();
  for (int i = 0; i <= 48; ++i) {
    sim_state_t state{};
    world.fill_state(state);
    for (auto& frame : vision.on_sim_state(state).frames)
      traffic.frames.push_back(std::move(frame));
    traffic.states.push_back(std::move(state));
    world.step();
  }
  return traffic;
}

}  // namespace ubersim::fuzz
