#pragma once
// Small builders shared by the radio emulator tests.
#include <cstdint>
#include <string>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/team_t.hpp>
#include <vector>

#include "ubersim/config.hpp"
#include "ubersim/radio/radio_profile.hpp"

namespace radio_test {

inline ubersim::robot_command_t velocity_command(std::int32_t id, double vx) {
  ubersim::robot_command_t c{};
  c.robot_id = id;
  c.mode = ubersim::robot_command_t::MODE_LOCAL_VELOCITY;
  c.vx = vx;
  return c;
}

// A packet for `team` with one local-velocity entry per id; vx encodes the
// sequence so a forwarded entry can be traced to the packet it came from.
inline ubersim::radio_packet_t packet(int team, std::int64_t sequence,
                                      const std::vector<std::int32_t>& ids) {
  ubersim::radio_packet_t p{};
  p.team = static_cast<std::int8_t>(team);
  p.sequence = sequence;
  p.t_sent = 0;
  for (auto id : ids) p.commands.push_back(velocity_command(id, 1e-4 * (sequence % 10000)));
  p.num_commands = static_cast<std::int32_t>(p.commands.size());
  return p;
}

// Ground truth with `per_team` robots of each team (ids 0..per_team-1, 4 wheels).
inline ubersim::sim_state_t state(double t, std::int64_t step, int per_team) {
  ubersim::sim_state_t s{};
  s.sim_time = t;
  s.step = step;
  s.dt = 1.0 / 240;
  // As fast as possible: the tests publish states as fast as they can, and
  // at speed 0 a packet arrives at the latest state's time. A real-time speed
  // would make the radio add the wall time since that state (docs/sync.md,
  // truth on demand), so the stamps would depend on how the test was scheduled.
  s.speed_factor = 0;
  for (int team = 0; team < 2; ++team) {
    for (int id = 0; id < per_team; ++id) {
      ubersim::robot_state_t r{};
      r.team = static_cast<std::int8_t>(team);
      r.robot_id = id;
      r.robot_type = "omni4_ssl";
      r.num_wheels = 4;
      r.wheel_speeds.assign(4, 0.0);
      r.last_command_time = -1;
      s.robots.push_back(r);
    }
  }
  s.num_robots = static_cast<std::int32_t>(s.robots.size());
  return s;
}

// A profile with every key given; tests override what they study.
inline std::string profile_text(double rate, double latency, double jitter, double packet_loss,
                                double robot_loss, double timeout = 0.25) {
  return "MAX_PACKET_RATE = " + std::to_string(rate) + "\nLATENCY = " + std::to_string(latency) +
         "\nLATENCY_JITTER = " + std::to_string(jitter) +
         "\nPACKET_LOSS = " + std::to_string(packet_loss) +
         "\nROBOT_LOSS = " + std::to_string(robot_loss) +
         "\nCOMMAND_TIMEOUT = " + std::to_string(timeout) +
         "\nFEEDBACK_RATE = 30\nFEEDBACK_LATENCY = 0.02\nFEEDBACK_LATENCY_JITTER = 0\n"
         "FEEDBACK_PACKET_LOSS = 0\nFEEDBACK_ROBOT_LOSS = 0\n"
         "LIMIT_SPEED = 10\nLIMIT_ANGULAR_SPEED = 60\nLIMIT_WHEEL_SPEED = 1000\n"
         "LIMIT_KICK_SPEED = 20\nLIMIT_DRIBBLER_SPEED = 5000\nSEED = 7\n";
}

inline ubersim::radio::RadioProfile profile(double rate, double latency, double jitter = 0,
                                            double packet_loss = 0, double robot_loss = 0) {
  return ubersim::radio::load_radio_profile(
      ubersim::ConfigFile::parse(profile_text(rate, latency, jitter, packet_loss, robot_loss),
                                 "test.cfg"),
      "test");
}

}  // namespace radio_test
