#pragma once
// What the demo team does with its robots, one function per mode. Each takes
// the world as seen through VISION and returns one command per own robot.
#include <string>
#include <ubersim/robot_command_t.hpp>
#include <vector>

#include "motion.hpp"
#include "world_model.hpp"

namespace demo {

struct TeamSetup {
  int defends = -1;           // which goal: -1 negative x, +1 positive x
  double field_length = 9.0;  // m
  double field_width = 6.0;   // m
  double kick_speed = 4.0;    // m/s
  int keeper_id = -1;         // the referee's goalkeeper; -1: the robot nearest our goal
  MotionLimits limits;
};

// Hold a formation in the own half.
std::vector<ubersim::robot_command_t> hold_positions(const WorldModel& world,
                                                     const TeamSetup& team);

// Every robot drives the figure-8 about its own formation spot (the paper's
// Figure 8 test), `speed` m/s, `size` m across.
std::vector<ubersim::robot_command_t> figure_eights(const WorldModel& world, const TeamSetup& team,
                                                    double speed, double size);

// A small game: a keeper on the goal line, the robot nearest the ball goes
// behind it and kicks at the opponent goal, the rest hold formation shifted
// towards the ball.
std::vector<ubersim::robot_command_t> play(const WorldModel& world, const TeamSetup& team);

}  // namespace demo
