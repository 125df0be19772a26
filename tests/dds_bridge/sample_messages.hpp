#pragma once
// LCM messages with a distinct value in every field (so a field copied into
// the wrong place, or not at all, shows), for the DDS bridge's tests and
// benchmark. `seed` shifts every value.
#include <cstdint>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/radio_feedback_t.hpp>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_commands_t.hpp>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/vision_frame_t.hpp>
#include <ubersim/vision_geometry_t.hpp>

namespace dds_test {

ubersim::vision_frame_t vision_frame(std::int64_t frame_number, int balls = 2,
                                     int robots_per_team = 6);
ubersim::field_geometry_t field_geometry(double seed = 0);
ubersim::vision_geometry_t vision_geometry(double seed = 0);
// Commands in local-velocity mode (no wheel speeds) and one in wheel-speed mode.
ubersim::robot_command_t velocity_command(std::int32_t robot_id, double seed = 0);
ubersim::robot_command_t wheel_command(std::int32_t robot_id, int wheels, double seed = 0);
ubersim::radio_packet_t radio_packet(std::int8_t team, std::int64_t sequence);
ubersim::radio_feedback_t radio_feedback(std::int8_t team, double seed = 0);
ubersim::sim_commands_t sim_commands(std::int8_t team, std::int64_t sequence);
// `robots_per_team` robots of each team, each with 4 wheel speeds.
ubersim::sim_state_t sim_state(std::int64_t step, int robots_per_team = 11);
ubersim::sim_control_t sim_control(std::int64_t request_id);
ubersim::sim_control_ack_t sim_control_ack(std::int64_t request_id);

}  // namespace dds_test
