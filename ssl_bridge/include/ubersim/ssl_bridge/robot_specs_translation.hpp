#pragma once
// SimulatorConfig.robot_specs -> robot types defined at run time. Each
// RobotSpecs becomes the text of a robot config file: the bridge's base robot
// type (--robot-type) with the keys the specs set replaced, which physics reads
// with the same reader as config/robots/ (SIM_CONTROL DEFINE_ROBOT_TYPE) and
// then builds the team's robots from. What cannot be honoured is an error
// naming the protocol field; the rest of the specs still apply.
#include <ssl_simulation_config.pb.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ubersim/config.hpp"
#include "ubersim/robot_config.hpp"
#include "ubersim/ssl_bridge/errors.hpp"

namespace ubersim::ssl {

// The robot type specs start from: its keys in file order, and its values.
struct BaseRobotType {
  std::vector<std::pair<std::string, std::vector<std::string>>> keys;
  RobotTypeConfig config;
  double ball_radius = 0.0215;  // m, a mouth (ER-Force's shoot_radius) must fit the ball
};

BaseRobotType base_robot_type(const ConfigFile& file, const RobotTypeConfig& config,
                              double ball_radius);

struct DefinedRobotType {
  std::string name;                 // ssl_specs_<team>[_<id>]
  std::string config_text;          // KEY = values lines
  double radius = 0;                // m
  int8_t team = 0;                  // team_t
  std::optional<int32_t> robot_id;  // unset: the whole team
};

struct RobotSpecsTranslation {
  std::vector<DefinedRobotType> types;
  Errors errors;
};

RobotSpecsTranslation translate_robot_specs(
    const google::protobuf::RepeatedPtrField<RobotSpecs>& specs, const BaseRobotType& base);

}  // namespace ubersim::ssl
