#include "sim_rig.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <ubersim/team_t.hpp>

#include "ubersim/common_options.hpp"
#include "ubersim/config.hpp"
#include "ubersim/config_paths.hpp"
#include "ubersim/topics.hpp"

namespace ubersim::report {
namespace {

constexpr double kStartTimeout = 30;  // s of wall time for a process to answer at all
constexpr double kReplyTimeout = 60;  // s of wall time for any later answer (a loaded machine)
constexpr double kTimeMatch = 1e-9;   // s: two sim times are the same instant
constexpr int kPingRobot = 0;         // BLUE_0 of the scenario

std::string tail(const std::string& text, std::size_t max_chars = 4000) {
  return text.size() <= max_chars ? text : "..." + text.substr(text.size() - max_chars);
}

}  // namespace

SimRig::SimRig(const RigPaths& paths, const RigOptions& options)
    : paths_(paths), options_(options), sender_("ubersim_report." + std::to_string(::getpid())) {
  std::filesystem::create_directories(paths_.work_dir);
  const std::string vision_profile = write_marker_profile(options_.vision_profile);
  const auto log = [&](const char* what) {
    return (std::filesystem::path(paths_.work_dir) / (options_.name + "_" + what + ".log"))
        .string();
  };
  const auto program = [&](const char* name) {
    return (std::filesystem::path(paths_.bin_dir) / name).string();
  };

  bus_ = std::make_unique<MessageBus>(with_receive_buffer(default_lcm_url()));
  truth_demand_ = std::make_unique<TruthDemandAnnouncer>(*bus_, channels_, sender_);
  truth_demand_->ask(every_step_demand);
  ubersim::subscribe(*bus_, channels_, topics::kSimState, [this](const sim_state_t& s) {
    // Physics publishes a step's state again after a placement and, while idle
    // in lockstep, once a second of wall time: handlers see each step once, so
    // that what they record does not depend on the wall clock.
    const bool new_step = s.step > state_.step || dispatched_step_ < 0;
    state_ = s;
    if (!new_step || s.step == dispatched_step_) return;
    dispatched_step_ = s.step;
    for (auto& handler : state_handlers_) handler(s);
  });
  ubersim::subscribe(*bus_, channels_, topics::kVision, [this](const vision_frame_t& f) {
    if (f.camera_id == marker_camera_) {
      marker_time_ = std::max(marker_time_, f.t_capture);
      return;
    }
    for (auto& handler : frame_handlers_) handler(f);
  });
  ubersim::subscribe(*bus_, channels_, topics::kSimControlAck, [this](const sim_control_ack_t& a) {
    if (a.sender == sender_) acks_[a.request_id] = a;
  });
  ubersim::subscribe(*bus_, channels_, topics::kSimCommands, [this](const sim_commands_t& c) {
    if (c.team == team_t::BLUE) ping_forwarded_ = c.sequence;
  });

  const std::string config_dir = paths_.config_dir;
  physics_ = std::make_unique<ChildProcess>(
      std::vector<std::string>{program("ubersim_physics"), "--lockstep", "--scenario",
                               options_.scenario, "--physics-config", paths_.physics_config,
                               "--config-dir", config_dir},
      log("physics"));
  sim_control_t ping{};
  ping.action = sim_control_t::PING;
  bool up = false;
  const auto start = std::chrono::steady_clock::now();
  while (!up && std::chrono::steady_clock::now() - start < std::chrono::seconds(30)) {
    if (!physics_->running()) fail("ubersim_physics exited at start");
    up = control(ping, 0.3);
  }
  if (!up) fail("ubersim_physics does not answer PING");

  vision_ = std::make_unique<ChildProcess>(
      std::vector<std::string>{program("ubersim_vision"), "--profile", vision_profile, "--seed",
                               std::to_string(options_.vision_seed), "--config-dir", config_dir},
      log("vision"));
  radio_ = std::make_unique<ChildProcess>(
      std::vector<std::string>{program("ubersim_radio"), "--yellow-profile", options_.radio_profile,
                               "--blue-profile", "ideal", "--seed",
                               std::to_string(options_.radio_seed), "--config-dir", config_dir},
      log("radio"));

  // Vision is up once it publishes a marker frame for a step; the radio
  // emulator once it forwards a ping (it needs a SIM_STATE for that).
  for (int attempt = 0;; ++attempt) {
    if (!vision_->running()) fail("ubersim_vision exited at start");
    raw_step(1);
    const double now = state_.sim_time;
    if (wait([&] { return marker_time_ >= now - kTimeMatch; }, 0.2)) break;
    if (attempt * 0.2 > kStartTimeout) fail("ubersim_vision publishes no frames");
  }
  for (int attempt = 0;; ++attempt) {
    if (!radio_->running()) fail("ubersim_radio exited at start");
    if (ping_radio(0.2)) break;
    if (attempt * 0.2 > kStartTimeout) fail("ubersim_radio forwards nothing");
    step(1);
  }
}

SimRig::~SimRig() {
  if (!stopped_) stop();
}

void SimRig::on_state(std::function<void(const sim_state_t&)> handler) {
  state_handlers_.push_back(std::move(handler));
}

void SimRig::on_frame(std::function<void(const vision_frame_t&)> handler) {
  frame_handlers_.push_back(std::move(handler));
}

std::string SimRig::write_marker_profile(const std::string& base_profile) {
  const std::filesystem::path base =
      std::filesystem::absolute(resolve_config(paths_.config_dir, "vision", base_profile));
  const std::int64_t cameras = ConfigFile::load(base).integer("CAMERA_COUNT");
  marker_camera_ = static_cast<int>(cameras);
  const std::string k = "CAMERA_" + std::to_string(cameras) + "_";
  const std::filesystem::path path =
      std::filesystem::path(paths_.work_dir) / (options_.name + "_vision.cfg");
  std::ofstream out(path);
  out << "# " << base.filename().string()
      << " plus a lockstep marker camera (written by the report; see sim_rig.hpp)\n"
      << "BASE = " << base.string() << "\n"
      << "CAMERA_COUNT = " << cameras + 1 << "\n"
      << k << "POSITION = 0 0 20           # m\n"
      << k << "ORIENTATION_DEG = 0 0 0     # deg\n"
      << k << "FOCAL_LENGTH = 10000        # px: it sees a few mm of the field\n"
      << k << "IMAGE_SIZE = 4 4            # px\n"
      << k << "PHASE = 0                   # s\n"
      << k << "FRAME_RATE = 240            # Hz: a frame for every physics step\n"
      << k << "LATENCY = 0                 # s\n"
      << k << "LATENCY_JITTER = 0          # s\n"
      << k << "PROCESSING_TIME = 0         # s\n";
  if (!out) throw std::runtime_error("cannot write " + path.string());
  return path.string();
}

template <class Done>
bool SimRig::wait(Done done, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!done()) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                          deadline - std::chrono::steady_clock::now())
                          .count();
    if (left <= 0) return false;
    truth_demand_->tick(std::chrono::steady_clock::now());
    bus_->wait_and_handle(static_cast<int>(std::min<long long>(left, 100)));
  }
  return true;
}

bool SimRig::control(sim_control_t request, double timeout_s, sim_control_ack_t* ack) {
  request.request_id = ++request_id_;
  request.sender = sender_;
  request.num_robots = static_cast<int32_t>(request.robots.size());
  const std::int64_t id = request.request_id;
  ubersim::publish(*bus_, channels_, topics::kSimControl, request);
  if (!wait([&] { return acks_.count(id) > 0; }, timeout_s)) return false;
  if (ack != nullptr) *ack = acks_[id];
  const bool ok = acks_[id].ok;
  acks_.erase(id);
  return ok;
}

void SimRig::place(sim_control_t request) {
  sim_control_ack_t ack{};
  if (request.action != sim_control_t::SETUP) request.action = sim_control_t::PLACE;
  if (!control(request, kReplyTimeout, &ack)) {
    fail("placement refused or unanswered: " + ack.message);
  }
}

void SimRig::raw_step(int steps) {
  sim_control_t request{};
  request.action = sim_control_t::STEP;
  request.step_count = steps;
  sim_control_ack_t ack{};
  if (!control(request, kReplyTimeout, &ack)) fail("STEP refused or unanswered: " + ack.message);
  // Physics publishes every SIM_STATE before the acknowledgement.
  if (state_.step != ack.step) fail("SIM_STATE of step " + std::to_string(ack.step) + " missing");
}

void SimRig::step(int steps) {
  raw_step(steps);
  const double now = state_.sim_time;
  if (!wait([&] { return marker_time_ >= now - kTimeMatch; }, kReplyTimeout)) {
    fail("no vision frame for sim time " + std::to_string(now));
  }
}

bool SimRig::ping_radio(double timeout_s) {
  radio_packet_t ping{};
  ping.team = team_t::BLUE;
  ping.sequence = ++ping_sequence_;
  ping.t_sent = state_.sim_time;
  robot_command_t stand_still{};
  stand_still.robot_id = kPingRobot;
  stand_still.mode = robot_command_t::MODE_LOCAL_VELOCITY;
  ping.commands.push_back(stand_still);
  ping.num_commands = 1;
  ubersim::publish(*bus_, channels_, topics::kRadio.of(Team::Blue), ping);
  const std::int64_t sequence = ping.sequence;
  return wait([&] { return ping_forwarded_ >= sequence; }, timeout_s);
}

void SimRig::send(radio_packet_t packet) {
  packet.team = team_t::YELLOW;
  packet.sequence = ++yellow_sequence_;
  packet.num_commands = static_cast<int32_t>(packet.commands.size());
  for (auto& c : packet.commands) c.num_wheels = static_cast<int32_t>(c.wheel_speeds.size());
  ubersim::publish(*bus_, channels_, topics::kRadio.of(Team::Yellow), packet);
  if (!ping_radio(kReplyTimeout)) fail("the radio emulator does not forward the blue ping");
}

void SimRig::fail(const std::string& what) {
  std::string text = options_.name + ": " + what;
  for (auto* p : {physics_.get(), vision_.get(), radio_.get()}) {
    if (p != nullptr) text += "\n--- " + p->name() + " log ---\n" + tail(p->log());
  }
  throw std::runtime_error(text);
}

std::string SimRig::stop() {
  stopped_ = true;
  std::string problems;
  // Emulators first: they would only complain about a silent physics.
  for (auto* p : {radio_.get(), vision_.get(), physics_.get()}) {
    if (p == nullptr) continue;
    const int code = p->stop();
    if (code != 0) {
      problems += p->name() + " exited with " + std::to_string(code) + "\n" + tail(p->log()) + "\n";
    }
  }
  return problems;
}

}  // namespace ubersim::report
