#pragma once
// SSL simulation protocol SimulatorCommand -> ubersim SIM_CONTROL requests.
// Unset fields mean "unchanged" in the protocol, so the latest SIM_STATE fills
// them in. Everything ubersim cannot do becomes an error for the response.
#include <ssl_simulation_control.pb.h>

#include <map>
#include <optional>
#include <string>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <utility>
#include <vector>

#include "ubersim/ssl_bridge/errors.hpp"
#include "ubersim/ssl_bridge/geometry_change_translation.hpp"
#include "ubersim/ssl_bridge/realism_translation.hpp"
#include "ubersim/ssl_bridge/robot_specs_translation.hpp"

namespace ubersim::ssl {

// Robot types earlier robot specs defined: robots added with present = true
// take them (a robot's own before its team's, before new_robot_type).
struct SpecTypes {
  std::map<std::pair<int8_t, int32_t>, std::string> by_robot;  // (team_t, id) -> type name
  std::map<int8_t, std::string> by_team;
  void record(const DefinedRobotType& type);
};

struct SimControlSettings {
  std::string new_robot_type = "omni4_ssl";  // type of a robot added with present = true
  SpecTypes spec_types;
  // What robot specs start from; null: robot specs are answered with an error.
  const BaseRobotType* base_robot_type = nullptr;
  // The field ubersim reports now (latest VISION_GEOMETRY), null before one came.
  const field_geometry_t* current_field = nullptr;
  double robot_radius = 0.09;   // m, for teleport_safely
  double ball_radius = 0.0215;  // m, for teleport_safely
};

struct SimControlTranslation {
  // In order; request_id and sender are left for the caller to set.
  std::vector<sim_control_t> requests;
  Errors errors;
  std::optional<int> vision_port;               // SimulatorConfig.vision_port, when valid
  std::vector<DefinedRobotType> defined_types;  // robot specs turned into robot types
  std::optional<emulator_realism_t> realism;    // for the emulators (EMULATOR_REALISM)
  std::optional<vision_cameras_t> cameras;      // for the vision emulator (VISION_CAMERAS)
};

// `state` is the latest SIM_STATE, or null when none arrived yet.
SimControlTranslation translate_simulator_command(const SimulatorCommand& command,
                                                  const sim_state_t* state,
                                                  const SimControlSettings& settings);

}  // namespace ubersim::ssl
