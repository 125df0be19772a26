// A small SSL team for sync mode through the bridge (docs/sync.md): a real
// process that speaks only the SSL protocols. It receives SSL-Vision
// detection packets on the multicast group, answers every one of them with
// one RobotControl on its team's port (an empty one when it has nothing to
// send: here every second packet), and first says hello with an empty
// RobotControl until the bridge responds. Its robots chase the ball and kick
// it; what it does depends only on the packets it received, so two runs that
// see the same packets send the same commands.
//   ssl_sync_team --team yellow|blue [--vision-port 10020] [--port 10301|10302]
#include <signal.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <map>
#include <string>

#include "ssl_client.hpp"

namespace {

volatile sig_atomic_t stop_requested = 0;

void on_signal(int) {
  stop_requested = 1;
}

struct Robot {
  double x = 0, y = 0, orientation = 0;  // m, m, rad
};

struct World {
  std::map<uint32_t, Robot> own;
  bool ball_seen = false;
  double ball_x = 0, ball_y = 0;  // m

  void update(const SSL_DetectionFrame& frame, bool yellow) {
    for (const SSL_DetectionRobot& r : yellow ? frame.robots_yellow() : frame.robots_blue()) {
      if (!r.has_robot_id()) continue;
      own[r.robot_id()] = {r.x() / 1000.0, r.y() / 1000.0, r.orientation()};
    }
    if (frame.balls_size() > 0) {
      ball_seen = true;
      ball_x = frame.balls(0).x() / 1000.0;
      ball_y = frame.balls(0).y() / 1000.0;
    }
  }
};

double clamp(double v, double limit) {
  return std::max(-limit, std::min(limit, v));
}

// Every robot drives at the ball (global velocity, turning to face it) and
// kicks when it is close.
RobotControl chase(const World& world) {
  RobotControl control;
  if (!world.ball_seen) return control;
  for (const auto& [id, robot] : world.own) {
    const double dx = world.ball_x - robot.x, dy = world.ball_y - robot.y;
    const double heading = std::atan2(dy, dx);
    const double turn = std::remainder(heading - robot.orientation, 2 * M_PI);
    RobotCommand* command = control.add_robot_commands();
    command->set_id(id);
    MoveGlobalVelocity* velocity = command->mutable_move_command()->mutable_global_velocity();
    velocity->set_x(static_cast<float>(clamp(1.5 * dx, 1.5)));
    velocity->set_y(static_cast<float>(clamp(1.5 * dy, 1.5)));
    velocity->set_angular(static_cast<float>(clamp(3.0 * turn, 4.0)));
    if (std::hypot(dx, dy) < 0.15) command->set_kick_speed(3.0f);
  }
  return control;
}

}  // namespace

int main(int argc, char** argv) {
  const std::optional<ssl_test::TeamArguments> arguments =
      ssl_test::parse_team_arguments(argc, argv, "ssl_sync_team");
  if (!arguments) return 2;
  if (arguments->grsim) {
    std::cerr << "ssl_sync_team: --protocol grsim: this team answers frames with RobotControl\n";
    return 2;
  }
  const bool yellow = arguments->yellow;
  const std::string team = yellow ? "yellow" : "blue";
  const int vision_port = arguments->vision_port;
  const int port = arguments->port;
  struct sigaction action {};
  action.sa_handler = on_signal;
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);

  // Join the group first: every detection packet after our hello is ours to answer.
  ssl_test::VisionReceiver vision("224.5.23.2", vision_port);
  ssl_test::UdpClient robots(port);
  const std::string nothing = RobotControl().SerializeAsString();
  bool heard = false;
  while (!stop_requested && !heard) {
    robots.send(nothing);
    heard = robots.receive(0.5).has_value();
  }
  std::cout << "ssl_sync_team " << team << ": the bridge answered our hello" << std::endl;

  World world;
  long packets = 0, with_commands = 0, responses = 0;
  while (!stop_requested) {
    const auto packet = vision.receive(0.1);
    while (robots.receive(0)) ++responses;              // errors and feedback: not used here
    if (!packet || !packet->has_detection()) continue;  // geometry needs no answer
    world.update(packet->detection(), yellow);
    ++packets;
    if (packets % 2 == 0) {
      robots.send(nothing);
      continue;
    }
    const RobotControl control = chase(world);
    if (control.robot_commands_size() > 0) ++with_commands;
    robots.send(control.SerializeAsString());
  }
  std::cout << "ssl_sync_team " << team << ": answered " << packets << " detection packets ("
            << with_commands << " with commands), " << responses << " responses" << std::endl;
  return 0;
}
