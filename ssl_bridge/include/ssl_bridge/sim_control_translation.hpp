#pragma once
// SSL simulation protocol SimulatorCommand -> ubersim SIM_CONTROL requests.
// Unset fields mean "unchanged" in the protocol, so the latest SIM_STATE fills
// them in. Everything ubersim cannot do becomes an error for the response.
#include <ssl_simulation_control.pb.h>

#include <optional>
#include <string>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <vector>

#include "ssl_bridge/errors.hpp"

namespace ubersim::ssl {

struct SimControlSettings {
  std::string new_robot_type = "omni4_ssl";  // type of a robot added with present = true
  double robot_radius = 0.09;                // m, for teleport_safely
  double ball_radius = 0.0215;               // m, for teleport_safely
};

struct SimControlTranslation {
  // In order; request_id and sender are left for the caller to set.
  std::vector<sim_control_t> requests;
  Errors errors;
  std::optional<int> vision_port;  // SimulatorConfig.vision_port, when valid
};

// `state` is the latest SIM_STATE, or null when none arrived yet.
SimControlTranslation translate_simulator_command(const SimulatorCommand& command,
                                                  const sim_state_t* state,
                                                  const SimControlSettings& settings);

}  // namespace ubersim::ssl
