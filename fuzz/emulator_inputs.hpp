#pragma once
// The input of fuzz_lcm_emulators: one byte that picks the channel, then the
// datagram as it arrives on it. Shared by the target and the seed writer.
#include <cstdint>

namespace ubersim::fuzz {

// The channels the vision and radio emulators take outside bytes from.
enum class EmulatorInput : std::uint8_t {
  RadioYellow,      // radio_packet_t -> radio emulator
  RadioBlue,        // radio_packet_t -> radio emulator
  SimState,         // sim_state_t -> both
  SimGeometry,      // field_geometry_t -> vision emulator
  EmulatorRealism,  // emulator_realism_t -> both
  VisionCameras,    // vision_cameras_t -> vision emulator
  Count
};

}  // namespace ubersim::fuzz
