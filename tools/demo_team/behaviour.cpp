#include "behaviour.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ubersim/angles.hpp"

namespace demo {
namespace {

constexpr double kRobotRadius = 0.09;   // m, SSL robots
constexpr double kBallRadius = 0.0215;  // m
// Our defence area (Division B: 1 m deep, 2 m wide) plus a margin: only the
// keeper may touch the ball in there, so the others leave such balls to it.
constexpr double kDefenceDepth = 1.0 + 0.25;      // m
constexpr double kDefenceHalfWidth = 1.0 + 0.25;  // m

// Formation spot of the n-th robot: a grid in the own half.
void formation_spot(const TeamSetup& team, int index, double& x, double& y) {
  const double half = team.field_length / 2;
  const int column = index % 3, row = index / 3;
  x = team.defends * half * (0.25 + 0.25 * column);
  y = (row % 2 == 0 ? 1 : -1) * ((row + 1) / 2) * team.field_width * 0.2 +
      (column - 1) * team.field_width * 0.08;
}

double facing_opponents(const TeamSetup& team) {
  return team.defends < 0 ? 0.0 : M_PI;
}

}  // namespace

std::vector<ubersim::robot_command_t> hold_positions(const WorldModel& world,
                                                     const TeamSetup& team) {
  std::vector<ubersim::robot_command_t> commands;
  int index = 0;
  for (const auto& [id, pose] : world.own()) {
    double x, y;
    formation_spot(team, index++, x, y);
    commands.push_back(go_to(id, pose, x, y, facing_opponents(team), team.limits));
  }
  return commands;
}

std::vector<ubersim::robot_command_t> figure_eights(const WorldModel& world, const TeamSetup& team,
                                                    double speed, double size) {
  std::vector<ubersim::robot_command_t> commands;
  int index = 0;
  for (const auto& [id, pose] : world.own()) {
    double x, y;
    formation_spot(team, index++, x, y);
    const PathPoint p = figure_eight(world.now(), x, y, size, speed);
    commands.push_back(track(id, pose, p.x, p.y, p.vx, p.vy, std::atan2(p.vy, p.vx), team.limits));
  }
  return commands;
}

std::vector<ubersim::robot_command_t> play(const WorldModel& world, const TeamSetup& team) {
  if (!world.ball()) return hold_positions(world, team);
  const auto& ball = *world.ball();
  const double half = team.field_length / 2;
  const double goal_x = -team.defends * half;  // the goal we attack

  // Keeper: the robot nearest our own goal; attacker: the nearest other robot to the ball.
  int keeper = -1, attacker = -1;
  double keeper_distance = std::numeric_limits<double>::infinity();
  if (world.own().count(team.keeper_id) > 0) {
    keeper = team.keeper_id;  // the rules let only this one into the defence area
  } else {
    for (const auto& [id, pose] : world.own()) {
      const double d = std::hypot(pose.x - team.defends * half, pose.y);
      if (d < keeper_distance) keeper_distance = d, keeper = id;
    }
  }
  double attacker_distance = std::numeric_limits<double>::infinity();
  for (const auto& [id, pose] : world.own()) {
    const double d = std::hypot(pose.x - ball.x, pose.y - ball.y);
    if (id != keeper && d < attacker_distance) attacker_distance = d, attacker = id;
  }

  std::vector<ubersim::robot_command_t> commands;
  int index = 0;
  for (const auto& [id, pose] : world.own()) {
    if (id == keeper) {
      const double x = team.defends * (half - kRobotRadius - 0.05);
      const double y = std::clamp(ball.y, -0.4, 0.4);
      commands.push_back(go_to(id, pose, x, y, facing_opponents(team), team.limits));
      continue;
    }
    const bool ball_in_our_area =
        ball.x * team.defends > half - kDefenceDepth && std::abs(ball.y) < kDefenceHalfWidth;
    if (id == attacker && !ball_in_our_area) {
      // Line up behind the ball on the ball-goal line, then drive through it and kick.
      const double ux = goal_x - ball.x, uy = -ball.y;
      const double n = std::hypot(ux, uy);
      const double dx = ux / n, dy = uy / n;
      const double heading = std::atan2(dy, dx);
      const double behind = kRobotRadius + kBallRadius + 0.06;
      const double bx = ball.x - dx * behind, by = ball.y - dy * behind;
      const bool lined_up = std::hypot(pose.x - bx, pose.y - by) < 0.05 &&
                            std::abs(ubersim::wrap_angle(heading - pose.orientation)) < 0.15;
      auto command =
          lined_up ? go_to(id, pose, ball.x + dx * 0.1, ball.y + dy * 0.1, heading, team.limits)
                   : go_to(id, pose, bx, by, heading, team.limits);
      if (lined_up) command.kick_speed = team.kick_speed;
      command.dribbler_speed = lined_up ? 300.0 : 0.0;
      commands.push_back(command);
      continue;
    }
    double x, y;
    formation_spot(team, index++, x, y);
    x += 0.3 * ball.x;  // follow the play a little
    commands.push_back(go_to(id, pose, x, y, facing_opponents(team), team.limits));
  }
  return commands;
}

}  // namespace demo
