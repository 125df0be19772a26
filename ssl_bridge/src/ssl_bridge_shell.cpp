#include "ssl_bridge_shell.hpp"

#include <chrono>
#include <optional>

#include "ubersim/config.hpp"
#include "ubersim/config_paths.hpp"
#include "ubersim/process_host.hpp"
#include "ubersim/robot_config.hpp"
#include "ubersim/spdlog.hpp"

namespace ubersim::ssl {
namespace {

// The grSim port's wake timer while nothing is due.
constexpr auto kIdle = std::chrono::hours(1);

// The SSL bridge's shell: the SslBridge (handed the host: its sockets, sync
// clients and truth demand) and the grSim port on the host's turns.
class SslBridgeShell {
 public:
  SslBridgeShell(SslBridgeOptions& options, const RobotTypeConfig& robot, ProcessHost& host)
      : options_(options), robot_(robot), host_(host), bridge_(host, options.bridge) {}
  SslBridgeShell(const SslBridgeShell&) = delete;
  SslBridgeShell& operator=(const SslBridgeShell&) = delete;

  int run() {
    host_.after_wake([this](ProcessHost::Clock::time_point now) { bridge_.tick(now); });
    if (options_.grsim.port > 0) start_grsim();
    bridge_.start();  // starts the team programs: every door of their group is open by now
    host_.at_stop([this] {
      bridge_.stop();
      bridge_.log_summary();
      if (grsim_) grsim_->log_summary();
    });
    return host_.run(std::chrono::milliseconds(50));
  }

 private:
  void start_grsim() {
    options_.grsim.listen_address = options_.bridge.listen_address;
    options_.grsim.sim_control = options_.bridge.sim_control;
    options_.grsim.translation.wheels = options_.bridge.wheels;
    options_.grsim.translation.spinner_speed = robot_.dribbler_max_speed;
    grsim_.emplace(host_.bus(), host_.channels(), options_.grsim);
    // grSim-protocol team programs under the time shim: the port is one more
    // door of the bridge's team group (docs/timeshim.md).
    const std::vector<Team> timed = grsim_teams(options_.bridge.teams);
    if (!timed.empty()) {
      grsim_->gate(
          timed,
          [this](Team team, radio_packet_t packet) {
            bridge_.publish_timed_radio(team, std::move(packet));
          },
          [this](const sockaddr_in& from) { return bridge_.program_of(from); });
      bridge_.add_timed_door(
          [this](std::int64_t now_ns, double settled) {
            return grsim_->drain_timed(now_ns, settled);
          },
          [this] { grsim_->release_replacements(); }, [this] { grsim_->stop_gating(); });
    }
    grsim_->start();
    // Wakes the loop when the grSim port has something due (a packet held
    // for its interval, a repeat, a stop); the work is done in tick().
    ProcessHost::Timer& wake = host_.every(kIdle, [](ProcessHost::Clock::time_point) {});
    host_.after_wake([this, &wake](ProcessHost::Clock::time_point now) {
      grsim_->tick(now);
      wake.due_at(grsim_->next_wake().value_or(now + kIdle));
    });
  }

  SslBridgeOptions& options_;
  const RobotTypeConfig& robot_;
  ProcessHost& host_;
  SslBridge bridge_;
  std::optional<GrsimPort> grsim_;
};

}  // namespace

int run_ssl_bridge(SslBridgeOptions& options) {
  const std::string config_dir = options.common.config_root();
  const RobotTypeConfig robot = load_robot_config(config_dir, options.robot_type);
  // Robot specs start from the same file (its keys, BASE chain resolved).
  options.bridge.base_robot_type = base_robot_type(
      ConfigFile::load(resolve_config(config_dir, "robots", options.robot_type)), robot,
      ConfigFile::load(resolve_config(config_dir, "balls", options.ball)).real("RADIUS"));
  options.bridge.sim_control.new_robot_type = options.robot_type;
  options.bridge.sim_control.robot_radius = robot.radius;
  options.bridge.wheels = wheel_mapping(robot);
  options.bridge.geometry.max_robot_radius = robot.radius;
  options.bridge.geometry.ball_model = load_ball_model(config_dir, options.ball);
  if (!options.bridge.wheels) {
    spdlog::warn(
        "robot type {} has no wheel in each quadrant: wheel_velocity commands will be "
        "answered with an error",
        options.robot_type);
  }

  ProcessHost host(options.common, "ssl_bridge");
  SslBridgeShell shell(options, robot, host);
  return shell.run();
}

}  // namespace ubersim::ssl
