#pragma once
// grSim's own protocol (grSim_Packet on UDP 20011) -> ubersim: a robot command
// -> robot_command_t (the bridge sends it on RADIO_<TEAM>), a replacement ->
// the simulation protocol's SimulatorCommand (translated to SIM_CONTROL like a
// team's teleport). What grSim does with each field is in its src/sslworld.cpp
// (SSLWorld::recvActions) and src/robot.cpp; docs/ssl_bridge.md says where
// ubersim follows it and where it cannot.
#include <grSim_Packet.pb.h>
#include <ssl_simulation_control.pb.h>

#include <optional>
#include <ubersim/robot_command_t.hpp>
#include <ubersim/sim_state_t.hpp>

#include "ubersim/ssl_bridge/errors.hpp"
#include "ubersim/ssl_bridge/robot_control_translation.hpp"

namespace ubersim::ssl {

// grSim has 16 robot slots per team (MAX_ROBOT_COUNT in its include/config.h);
// it ignores an id beyond them, and so does the bridge (counted).
inline constexpr unsigned kGrsimMaxRobots = 16;

// grSim reports a kick as a chip when kickspeedz >= 1 m/s (Kicker::kick).
enum class GrsimKick { None, Flat, Chip };

struct GrsimRobotCommand {
  robot_command_t command{};         // robot_id, motion, kick, dribbler
  GrsimKick kick = GrsimKick::None;  // what grSim's status would call the kick asked for
};

struct GrsimTranslationSettings {
  std::optional<WheelMapping> wheels;  // the robot type's, for wheelsspeed
  double spinner_speed = 0;            // rad/s of the roller while `spinner` is on
};

// One robot's command. `previous` is the robot's last command (null: none):
// a wheel grSim is not given keeps its previous speed, as in grSim. nullopt
// (and an error) when the command cannot be applied (not finite, wheels on a
// robot type without one wheel per quadrant).
std::optional<GrsimRobotCommand> translate_grsim_robot_command(
    const grSim_Robot_Command& in, const GrsimTranslationSettings& settings,
    const robot_command_t* previous, Errors& errors);

// The replacement as the simulation protocol's teleports: robots at x, y, dir
// (degrees), stopped, `turnon` false removes one and true (the default) adds
// one that is not on the field; the ball at x, y with vx, vy, an unset one
// keeping the ball's current value (from `state`). Robots without an id or
// beyond kGrsimMaxRobots are left out with an error.
SimulatorCommand grsim_replacement_command(const grSim_Replacement& in, const sim_state_t* state,
                                           Errors& errors);

}  // namespace ubersim::ssl
