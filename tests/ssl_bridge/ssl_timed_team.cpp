// An SSL team written the way real team software is, for the time shim
// (docs/timeshim.md, "Integration with sync mode"): nothing of ubersim and no
// answer per frame. A receiver thread takes SSL-Vision detection packets from
// the multicast group (poll with a timeout); the main loop runs at its own
// 50 Hz (sleep_until on the steady clock), drives its robots at the latest
// ball seen and sends one RobotControl per loop on its team's port, reading
// the responses without blocking. Each loop prints its own clocks:
//   loop N steady S.SSSSSSSSS wall W.WWWWWW packets P
// Started under the shim, S is sim time and the loop's commands are stamped
// with it; its behaviour depends only on what it received and when. With
// --protocol grsim it speaks grSim's protocol instead, as grSim clients do:
// one grSim_Packet per loop to grSim's command port (robot-local velocities),
// and no answer to read. The yellow team of the SSL protocol also teleports
// the ball once, at its loop 41 (0.82 s), on the simulation control port, as
// team software does (Utama-Core places the ball): physics must apply it at
// the state of the next frame on every run. 0.82 s lies between two frames'
// states with a capture instant's state (no frame) between it and the next
// frame: a command released there applied at whichever step physics had reached.
//   ssl_timed_team --team yellow|blue [--vision-port 10020] [--port 10301|10302|20011]
//                  [--protocol ssl|grsim]
#include <grSim_Packet.pb.h>
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

struct Pose {
  double x = 0, y = 0, orientation = 0;  // m, rad
};

struct Seen {
  std::map<uint32_t, Pose> own;  // by robot id
  bool ball = false;
  double ball_x = 0, ball_y = 0;  // m
  long packets = 0;
};

class World {
 public:
  void update(const SSL_DetectionFrame& frame, bool yellow) {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (const SSL_DetectionRobot& r : yellow ? frame.robots_yellow() : frame.robots_blue()) {
      if (r.has_robot_id()) {
        seen_.own[r.robot_id()] = {r.x() / 1000.0, r.y() / 1000.0, r.orientation()};
      }
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

// Each robot's velocity towards the ball (m/s, field frame), by robot id.
std::map<uint32_t, std::pair<double, double>> velocities_at_ball(const Seen& seen) {
  std::map<uint32_t, std::pair<double, double>> velocities;
  if (!seen.ball) return velocities;
  for (const auto& [id, at] : seen.own) {
    velocities[id] = {clamp(1.5 * (seen.ball_x - at.x), 1.5),
                      clamp(1.5 * (seen.ball_y - at.y), 1.5)};
  }
  return velocities;
}

// The ball to the centre circle's edge, still.
std::string teleport_ball() {
  SimulatorCommand command;
  TeleportBall* ball = command.mutable_control()->mutable_teleport_ball();
  ball->set_x(0.5f);
  ball->set_y(0.0f);
  ball->set_vx(0.0f);
  ball->set_vy(0.0f);
  return command.SerializeAsString();
}

std::string drive_at_ball(const Seen& seen) {
  RobotControl control;
  for (const auto& [id, v] : velocities_at_ball(seen)) {
    RobotCommand* command = control.add_robot_commands();
    command->set_id(id);
    MoveGlobalVelocity* global = command->mutable_move_command()->mutable_global_velocity();
    global->set_x(static_cast<float>(v.first));
    global->set_y(static_cast<float>(v.second));
    global->set_angular(0.0f);
  }
  return control.SerializeAsString();
}

// The same in grSim's protocol: velocities in the robot's frame.
std::string drive_at_ball_grsim(const Seen& seen, bool yellow) {
  grSim_Packet packet;
  grSim_Commands* commands = packet.mutable_commands();
  commands->set_timestamp(0);
  commands->set_isteamyellow(yellow);
  for (const auto& [id, v] : velocities_at_ball(seen)) {
    const double heading = seen.own.at(id).orientation;
    grSim_Robot_Command* command = commands->add_robot_commands();
    command->set_id(id);
    command->set_veltangent(
        static_cast<float>(std::cos(heading) * v.first + std::sin(heading) * v.second));
    command->set_velnormal(
        static_cast<float>(-std::sin(heading) * v.first + std::cos(heading) * v.second));
    command->set_velangular(0.0f);
    command->set_kickspeedx(0.0f);
    command->set_kickspeedz(0.0f);
    command->set_spinner(false);
    command->set_wheelsspeed(false);
  }
  return packet.SerializeAsString();
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
  constexpr int kControlPort = 10300;  // the SSL simulation protocol's control port
  constexpr long kTeleportLoop = 41;
  ssl_test::UdpClient control(kControlPort);
  const bool teleports = yellow && !arguments->grsim;
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
    robots.send(arguments->grsim ? drive_at_ball_grsim(seen, yellow) : drive_at_ball(seen));
    while (robots.receive(0)) ++responses;  // errors and feedback: not used here
    if (teleports && loops == kTeleportLoop) control.send(teleport_ball());
    while (control.receive(0)) {
    }
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
