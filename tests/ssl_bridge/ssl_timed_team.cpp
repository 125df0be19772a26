// An SSL team written the way real team software is, for the time shim
// (docs/timeshim.md, "Integration with sync mode"): nothing of ubersim and no
// answer per frame. A receiver thread takes SSL-Vision detection packets from
// the multicast group (poll with a timeout); the main loop runs at its own
// 50 Hz (sleep_until on the steady clock), drives its robots at the latest
// ball seen and sends one RobotControl per loop on its team's port, reading
// the responses without blocking. Each loop prints its own clocks:
//   loop N steady S.SSSSSSSSS wall W.WWWWWW packets P
// Started under the shim, S is sim time and the loop's commands are stamped
// with it; its behaviour depends only on what it received and when.
//   ssl_timed_team --team yellow|blue [--vision-port 10020] [--port 10301|10302]
#include <signal.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <mutex>
#include <string>
#include <thread>

#include "ssl_client.hpp"

namespace {

std::atomic<bool> stop_requested{false};

void on_signal(int) {
  stop_requested = true;
}

struct Seen {
  std::map<uint32_t, std::pair<double, double>> own;  // id -> x, y (m)
  bool ball = false;
  double ball_x = 0, ball_y = 0;  // m
  long packets = 0;
};

class World {
 public:
  void update(const SSL_DetectionFrame& frame, bool yellow) {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (const SSL_DetectionRobot& r : yellow ? frame.robots_yellow() : frame.robots_blue()) {
      if (r.has_robot_id()) seen_.own[r.robot_id()] = {r.x() / 1000.0, r.y() / 1000.0};
    }
    if (frame.balls_size() > 0) {
      seen_.ball = true;
      seen_.ball_x = frame.balls(0).x() / 1000.0;
      seen_.ball_y = frame.balls(0).y() / 1000.0;
    }
    ++seen_.packets;
  }
  Seen get() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return seen_;
  }

 private:
  mutable std::mutex mutex_;
  Seen seen_;
};

double clamp(double v, double limit) {
  return std::max(-limit, std::min(limit, v));
}

RobotControl drive_at_ball(const Seen& seen) {
  RobotControl control;
  if (!seen.ball) return control;
  for (const auto& [id, at] : seen.own) {
    RobotCommand* command = control.add_robot_commands();
    command->set_id(id);
    MoveGlobalVelocity* v = command->mutable_move_command()->mutable_global_velocity();
    v->set_x(static_cast<float>(clamp(1.5 * (seen.ball_x - at.first), 1.5)));
    v->set_y(static_cast<float>(clamp(1.5 * (seen.ball_y - at.second), 1.5)));
    v->set_angular(0.0f);
  }
  return control;
}

double seconds_of(std::chrono::nanoseconds d) {
  return static_cast<double>(d.count()) / 1e9;
}

}  // namespace

int main(int argc, char** argv) {
  const std::optional<ssl_test::TeamArguments> arguments =
      ssl_test::parse_team_arguments(argc, argv, "ssl_timed_team");
  if (!arguments) return 2;
  const bool yellow = arguments->yellow;
  const std::string team = yellow ? "yellow" : "blue";
  const int vision_port = arguments->vision_port;
  const int port = arguments->port;
  struct sigaction action {};
  action.sa_handler = on_signal;
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);

  ssl_test::VisionReceiver vision("224.5.23.2", vision_port);
  ssl_test::UdpClient robots(port);
  World world;
  std::thread receiver([&] {
    while (!stop_requested) {
      const auto packet = vision.receive(0.25);  // poll with a timeout
      if (packet && packet->has_detection()) world.update(packet->detection(), yellow);
    }
  });

  using Steady = std::chrono::steady_clock;
  constexpr auto kPeriod = std::chrono::milliseconds(20);
  const auto start = Steady::now();
  auto next = start;
  long loops = 0, responses = 0;
  while (!stop_requested) {
    const Seen seen = world.get();
    robots.send(drive_at_ball(seen).SerializeAsString());
    while (robots.receive(0)) ++responses;  // errors and feedback: not used here
    const auto now = Steady::now();
    const double wall = seconds_of(std::chrono::system_clock::now().time_since_epoch());
    std::printf("loop %ld steady %.9f wall %.6f packets %ld\n", loops++,
                seconds_of(now.time_since_epoch()), wall, seen.packets);
    std::fflush(stdout);
    next += kPeriod;
    std::this_thread::sleep_until(next);
  }
  receiver.join();
  std::printf("ssl_timed_team %s: %ld loops, %ld responses\n", team.c_str(), loops, responses);
  return 0;
}
