#include "vision_test_support.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/team_t.hpp>

#include "ubersim/common_options.hpp"
#include "ubersim/topics.hpp"

extern char** environ;

namespace vision_test {

using Clock = std::chrono::steady_clock;

std::string vision_program() {
  return UBERSIM_VISION_PROGRAM;
}
std::string config_dir() {
  return UBERSIM_SOURCE_CONFIG_DIR;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string marker_camera_keys(int id) {
  const std::string k = "CAMERA_" + std::to_string(id) + "_";
  return k + "POSITION = 0 0 20\n" + k + "ORIENTATION_DEG = 0 0 0\n" + k +
         "FOCAL_LENGTH = 10000\n" + k + "IMAGE_SIZE = 4 4\n" + k + "PHASE = 0\n" + k +
         "FRAME_RATE = 240\n" + k + "LATENCY = 0\n" + k + "LATENCY_JITTER = 0\n" + k +
         "PROCESSING_TIME = 0\n";
}

std::map<std::string, long> exit_summary(const std::string& log_text) {
  std::map<std::string, long> counts;
  const auto at = log_text.find("summary:");
  if (at == std::string::npos) return counts;
  const std::string line = log_text.substr(at, log_text.find('\n', at) - at);
  const std::regex item(R"(([a-z ]+?) (\d+)(?:[,;]|$))");
  for (std::sregex_iterator it(line.begin(), line.end(), item), end; it != end; ++it) {
    std::string name = (*it)[1];
    name.erase(0, name.find_first_not_of(' '));
    if (name.rfind("summary: ", 0) == 0) name.erase(0, 9);
    counts[name] = std::stol((*it)[2]);
  }
  return counts;
}

ubersim::sim_state_t make_state(std::int64_t step, const Truth& truth) {
  ubersim::sim_state_t s{};
  s.sim_time = static_cast<double>(step) * kDt;
  s.step = step;
  s.dt = kDt;
  s.speed_factor = 0;
  s.ball_present = truth.ball_present;
  for (int i = 0; i < 3; ++i) s.ball.position[i] = truth.ball[i];
  s.ball.orientation[0] = 1;
  for (const TruthRobot& t : truth.robots) {
    ubersim::robot_state_t r{};
    r.team = t.team;
    r.robot_id = t.id;
    r.robot_type = t.type;
    r.x = t.x;
    r.y = t.y;
    r.orientation = t.orientation;
    r.body.position[0] = t.x;
    r.body.position[1] = t.y;
    r.body.orientation[0] = std::cos(t.orientation / 2);
    r.body.orientation[3] = std::sin(t.orientation / 2);
    r.last_command_time = -1;
    s.robots.push_back(r);
  }
  s.num_robots = static_cast<std::int32_t>(s.robots.size());
  return s;
}

ubersim::field_geometry_t division_b_geometry() {
  ubersim::field_geometry_t g{};
  g.name = "division_b";
  g.field_length = 9.0;
  g.field_width = 6.0;
  g.boundary_width = 0.3;
  g.line_width = 0.01;
  g.goal_width = 1.0;
  g.goal_depth = 0.18;
  g.goal_height = 0.155;
  g.goal_wall_thickness = 0.02;
  g.wall_height = 0.1;
  g.wall_thickness = 0.05;
  g.center_circle_radius = 0.5;
  g.penalty_area_depth = 1.0;
  g.penalty_area_width = 2.0;
  g.ball_radius = 0.0215;
  return g;
}

SimDriver::SimDriver() : bus_(ubersim::with_receive_buffer(ubersim::default_lcm_url())) {
  ubersim::subscribe(bus_, channels_, ubersim::topics::kVision,
                     std::function<void(const ubersim::vision_frame_t&)>(
                         [this](const ubersim::vision_frame_t& frame) { on_frame(frame); }),
                     100000);
  ubersim::subscribe(
      bus_, channels_, ubersim::topics::kVisionGeometry,
      std::function<void(const ubersim::vision_geometry_t&)>(
          [this](const ubersim::vision_geometry_t& g) { geometries_.push_back(g); }));
  ubersim::subscribe(
      bus_, channels_, ubersim::topics::kSimControl,
      std::function<void(const ubersim::sim_control_t&)>([this](const ubersim::sim_control_t& c) {
        if (c.action == ubersim::sim_control_t::REQUEST_GEOMETRY) emulator_ready_ = true;
      }));
}

void SimDriver::on_frame(const ubersim::vision_frame_t& frame) {
  double& newest = newest_capture_[frame.camera_id];
  newest = std::max(newest, frame.t_capture);
  if (marker_ < 0) {
    received_.push_back({frame, -1});
    return;
  }
  if (frame.camera_id != marker_) {
    since_marker_.push_back(frame);
    return;
  }
  if (std::abs(frame.t_capture - current_time_) < 1e-9) marker_seen_ = true;
  for (auto& f : since_marker_) received_.push_back({std::move(f), current_step_});
  since_marker_.clear();
}

bool SimDriver::wait_for(const std::function<bool()>& done, double timeout_s) {
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
  while (!done()) {
    if (Clock::now() > deadline) return false;
    bus_.wait_and_handle(20);
  }
  return true;
}

bool SimDriver::wait_for_emulator(const ubersim::field_geometry_t& geometry, double timeout_s) {
  if (!wait_for([this] { return emulator_ready_; }, timeout_s)) {
    failure_ = "the emulator never asked for the geometry";
    return false;
  }
  publish_geometry(geometry);
  return true;
}

void SimDriver::publish_state(const ubersim::sim_state_t& state) {
  ubersim::publish(bus_, channels_, ubersim::topics::kSimState, state);
}

void SimDriver::publish_raw_state(const std::vector<std::uint8_t>& bytes) {
  bus_.publish_encoded(ubersim::channel_name(channels_, ubersim::topics::kSimState), bytes.data(),
                       bytes.size());
}

void SimDriver::publish_cameras(const ubersim::vision_cameras_t& cameras) {
  ubersim::publish(bus_, channels_, ubersim::topics::kVisionCameras, cameras);
}

void SimDriver::publish_geometry(const ubersim::field_geometry_t& geometry) {
  ubersim::publish(bus_, channels_, ubersim::topics::kSimGeometry, geometry);
}

void SimDriver::listen(double seconds) {
  wait_for([] { return false; }, seconds);
}

bool SimDriver::run_lockstep(std::int64_t first, std::int64_t last, const World& world,
                             int marker) {
  marker_ = marker;
  for (std::int64_t step = first; step <= last; ++step) {
    current_step_ = step;
    current_time_ = static_cast<double>(step) * kDt;
    marker_seen_ = false;
    publish_state(make_state(step, world(current_time_)));
    if (!wait_for([this] { return marker_seen_; }, 10.0)) {
      failure_ = "no marker frame for step " + std::to_string(step);
      return false;
    }
  }
  return true;
}

bool SimDriver::run_windowed(std::int64_t first, std::int64_t last, const World& world, double lead,
                             int camera_count) {
  auto newest_of_all = [this, camera_count] {
    double newest = 1e300;
    for (int c = 0; c < camera_count; ++c) {
      const auto found = newest_capture_.find(c);
      newest = std::min(newest, found == newest_capture_.end() ? 0.0 : found->second);
    }
    return newest;
  };
  for (std::int64_t step = first; step <= last; ++step) {
    const double t = static_cast<double>(step) * kDt;
    if (!wait_for([&] { return t - newest_of_all() <= lead; }, 10.0)) {
      failure_ = "the emulator stopped publishing before step " + std::to_string(step);
      return false;
    }
    bus_.handle_pending();
    publish_state(make_state(step, world(t)));
  }
  return true;
}

std::vector<Received> SimDriver::frames(int camera) const {
  std::vector<Received> out;
  for (const Received& r : received_) {
    if (r.frame.camera_id == camera) out.push_back(r);
  }
  for (const auto& f : since_marker_) {
    if (f.camera_id == camera) out.push_back({f, -1});
  }
  return out;
}

}  // namespace vision_test
