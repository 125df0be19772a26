#pragma once
// The bridge's state a datagram meets in a running game: the shipped robot
// type as the base of robot specs and wheel mapping, the Division B field, and
// a SIM_STATE with robots of both teams. Built once per fuzzer process.
#include <optional>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/sim_state_t.hpp>

#include "ubersim/ssl_bridge/robot_control_translation.hpp"
#include "ubersim/ssl_bridge/sim_control_translation.hpp"

namespace ubersim::fuzz {

struct SslFixture {
  ssl::BaseRobotType base;
  std::optional<ssl::WheelMapping> wheels;
  field_geometry_t field{};
  sim_state_t state{};
  ssl::SimControlSettings settings;  // points into this fixture

  static SslFixture& instance();
};

}  // namespace ubersim::fuzz
