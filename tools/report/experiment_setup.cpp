#include "experiment_setup.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <ubersim/team_t.hpp>

#include "ubersim/config.hpp"
#include "ubersim/config_paths.hpp"

namespace ubersim::report {

ExperimentSetup::ExperimentSetup(RigPaths paths, std::string ball)
    : paths_(std::move(paths)), ball_name_(std::move(ball)) {
  std::filesystem::create_directories(paths_.work_dir);
  gravity_ = ConfigFile::load(resolve_config(paths_.config_dir, "physics", paths_.physics_config))
                 .real("GRAVITY");
  ball_ = physics::load_ball_config(paths_.config_dir, ball_name_);
}

RobotTypeConfig ExperimentSetup::robot(const std::string& type) const {
  return load_robot_config(paths_.config_dir, type);
}

double ExperimentSetup::radio_latency(const std::string& profile) const {
  return ConfigFile::load(resolve_config(paths_.config_dir, "radio", profile)).real("LATENCY");
}

std::string ExperimentSetup::write(const std::string& name, const std::string& text) const {
  std::string path = (std::filesystem::path(paths_.work_dir) / name).string();
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path);
  return path;
}

std::string ExperimentSetup::drive_scenario(const std::string& type) const {
  std::ostringstream s;
  s << "# Written by the report: one " << type << " with room to accelerate.\n"
    << "FIELD = division_a\nBALL = " << ball_name_ << "\nBALL_POSITION = 5.8 4.3  # m\n"
    << "YELLOW_0 = " << type << " -5.5 0 0\n"
    << "BLUE_0 = omni4_ssl_planar 5.8 -4.3 180  # the rig's ping robot\n";
  return write("drive_" + type + ".cfg", s.str());
}

std::string ExperimentSetup::centre_scenario(const std::string& type) const {
  std::ostringstream s;
  s << "# Written by the report: one " << type << " at the centre.\n"
    << "FIELD = division_b\nBALL = " << ball_name_ << "\nBALL_POSITION = 4.3 2.8  # m\n"
    << "YELLOW_0 = " << type << " 0 0 0\n"
    << "BLUE_0 = omni4_ssl_planar 4.3 -2.8 180  # the rig's ping robot\n";
  return write("centre_" + type + ".cfg", s.str());
}

std::string ExperimentSetup::hall_scenario(const std::string& type) const {
  const std::filesystem::path base =
      std::filesystem::absolute(resolve_config(paths_.config_dir, "fields", "division_b"));
  const std::string field =
      write("hall_field.cfg",
            "# Written by the report: a long carpet for ball roll-out.\n"
            "BASE = " +
                base.string() + "\nFIELD_LENGTH = 44.0  # m\nFIELD_WIDTH = 4.0  # m\n");
  std::ostringstream s;
  s << "# Written by the report: the roll-out hall.\n"
    << "FIELD = " << field << "\nBALL = " << ball_name_ << "\nBALL_POSITION = 21 1.5  # m\n"
    << "YELLOW_0 = " << type << " " << kHallStartX << " 0 0\n"
    << "BLUE_0 = omni4_ssl_planar 21 -1.5 180  # the rig's ping robot\n";
  return write("hall_" + type + ".cfg", s.str());
}

bool find_robot(const sim_state_t& state, int id, RobotSample& out) {
  for (const auto& r : state.robots) {
    if (r.team != team_t::YELLOW || r.robot_id != id) continue;
    out = RobotSample{state.sim_time, r.x, r.y, r.orientation, r.vx, r.vy};
    return true;
  }
  return false;
}

bool find_detection(const vision_frame_t& frame, int id, RobotDetection& out) {
  for (const auto& r : frame.robots_yellow) {
    if (r.robot_id != id) continue;
    out = RobotDetection{frame.t_capture, r.x, r.y, r.orientation};
    return true;
  }
  return false;
}

BallSample ball_sample(const sim_state_t& state) {
  const auto& b = state.ball;
  return BallSample{state.sim_time,       b.position[0],        b.position[1],       b.position[2],
                    b.linear_velocity[0], b.linear_velocity[1], b.linear_velocity[2]};
}

sim_control_t place_robot(int id, double x, double y, double heading) {
  sim_control_t request{};
  request.action = sim_control_t::PLACE;
  robot_placement_t p{};
  p.team = team_t::YELLOW;
  p.robot_id = id;
  p.present = true;
  p.x = x;
  p.y = y;
  p.orientation = heading;
  request.robots.push_back(p);
  return request;
}

void place_ball(sim_control_t& request, double x, double y, double z, double vx, double vy,
                double vz) {
  request.has_ball = true;
  request.ball.position[0] = x;
  request.ball.position[1] = y;
  request.ball.position[2] = z;
  request.ball.linear_velocity[0] = vx;
  request.ball.linear_velocity[1] = vy;
  request.ball.linear_velocity[2] = vz;
}

void send_stop(SimRig& rig, int robot_id) {
  const double until = rig.time() + 0.3;
  while (rig.time() < until) {
    radio_packet_t packet{};
    packet.t_sent = rig.time();
    robot_command_t stop{};
    stop.robot_id = robot_id;
    stop.mode = robot_command_t::MODE_LOCAL_VELOCITY;
    packet.commands.push_back(stop);
    rig.send(packet);
    rig.step(kStepsPerCommand);
  }
}

}  // namespace ubersim::report
