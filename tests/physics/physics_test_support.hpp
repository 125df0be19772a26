#pragma once
// Helpers shared by the physics behaviour tests: worlds built from the
// shipped configs (real ODE, no mocks), with the drive model chosen per test.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <ubersim/robot_command_t.hpp>

#include "ubersim/physics/world.hpp"

namespace ubersim::physics::testing {

inline const std::string kConfigDir = UBERSIM_SOURCE_CONFIG_DIR;

// Robot types from config/robots with the drive model replaced by `model`
// (so every type is tested with both models).
inline RobotTypeSource types_with_model(DriveModel model) {
  auto base = robot_types_from(kConfigDir);
  return [base, model](const std::string& name) {
    auto type = std::make_shared<RobotTypeConfig>(*base(name));
    type->model = model;
    return std::shared_ptr<const RobotTypeConfig>(type);
  };
}

// A field with the ball in a corner and no robots.
inline WorldSetup empty_world(DriveModel model, const std::string& field = "division_b") {
  WorldSetup setup;
  setup.field = load_field_config(kConfigDir, field);
  setup.ball = load_ball_config(kConfigDir, "ssl_golf_ball");
  setup.physics = load_physics_config(kConfigDir, "default");
  setup.ball_x = -setup.field.field_length / 2 + 0.3;
  setup.ball_y = -setup.field.field_width / 2 + 0.3;
  setup.robot_types = types_with_model(model);
  return setup;
}

// The text of a shipped robot config with the drive model of the test and
// some keys replaced or added ("KEY" -> "values"): a robot type to define at
// run time (World::define_robot_type reads it like config/robots/).
inline std::string robot_config_text(const std::string& name, DriveModel model,
                                     std::map<std::string, std::string> keys) {
  keys["DRIVE_MODEL"] = model == DriveModel::Jointed ? "jointed" : "planar";
  const ConfigFile file = ConfigFile::load(kConfigDir + "/robots/" + name + ".cfg");
  std::string text;
  for (const std::string& key : file.keys()) {
    if (keys.count(key) != 0) continue;
    text += key + " =";
    for (const std::string& v : file.strings(key)) text += " " + v;
    text += "\n";
  }
  for (const auto& [key, values] : keys) text += key + " = " + values + "\n";
  return text;
}

inline robot_command_t velocity_command(int id, double vx, double vy, double omega) {
  robot_command_t c{};
  c.robot_id = id;
  c.mode = robot_command_t::MODE_LOCAL_VELOCITY;
  c.vx = vx;
  c.vy = vy;
  c.omega = omega;
  c.num_wheels = 0;
  return c;
}

inline void run_for(World& world, double seconds) {
  const auto steps = static_cast<long>(std::lround(seconds / world.dt()));
  for (long i = 0; i < steps; ++i) world.step();
}

inline const char* model_name(DriveModel m) {
  return m == DriveModel::Jointed ? "jointed" : "planar";
}

inline double ball_speed(const World& w) {
  const dReal* v = w.ball().velocity();
  return std::hypot(v[0], v[1]);
}

}  // namespace ubersim::physics::testing

namespace ubersim::physics::testing {
// Names parameterised tests after the drive model (a function, not a lambda:
// gtest's macro would shadow a lambda's parameter).
inline std::string drive_model_test_name(const ::testing::TestParamInfo<DriveModel>& param_info) {
  return model_name(param_info.param);
}
}  // namespace ubersim::physics::testing
