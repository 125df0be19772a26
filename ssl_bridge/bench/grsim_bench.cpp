// ubersim_grsim_bench: what grSim's protocol costs (docs/ssl_bridge.md,
// "grSim's protocol"). Runs the real bridge and radio emulator (profile
// `ideal`: no rate limit or delay, so what is measured is the pipeline) on a
// private LCM URL and ports, stands in for physics (SIM_STATE at 240 Hz with
// 11 robots per team), and in the same run measures
//   * command latency: a grSim packet sent -> the SIM_COMMANDS carrying it,
//     without a flood and under a flood of --rate packets/s (one robot per
//     packet, both teams), and their ratio;
//   * CPU of the bridge and the radio emulator per 10,000 grSim packets
//     during the flood, and their CPU share of one core quiet and flooded.
#include <arpa/inet.h>
#include <grSim_Packet.pb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <ubersim/sim_commands_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/team_t.hpp>
#include <vector>

#include "grsim_packet.hpp"
#include "temp_folder.hpp"
#include "ubersim/child_process.hpp"
#include "ubersim/cli.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/process_main.hpp"

namespace {

using Clock = std::chrono::steady_clock;

struct Options {
  std::string lcm_url = "udpm://239.255.76.67:7711?ttl=0";
  int base_port = 27000;  // the bridge's ports: base .. base + 8
  int rate = 50'000;      // flood packets/s
  double seconds = 5;     // flood duration
  int probes = 100;       // latency probes per phase
};

// utime + stime of a process, in s.
double cpu_seconds(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::istringstream fields(text.substr(text.rfind(')') + 2));
  std::string field;
  double ticks = 0;
  for (int i = 3; i <= 15 && fields >> field; ++i) {
    if (i == 14 || i == 15) ticks += std::stod(field);
  }
  return ticks / static_cast<double>(::sysconf(_SC_CLK_TCK));
}

class Sender {
 public:
  explicit Sender(int port) : fd_(::socket(AF_INET, SOCK_DGRAM, 0)) {
    to_.sin_family = AF_INET;
    to_.sin_port = htons(static_cast<uint16_t>(port));
    ::inet_pton(AF_INET, "127.0.0.1", &to_.sin_addr);
  }
  ~Sender() { ::close(fd_); }
  Sender(const Sender&) = delete;
  Sender& operator=(const Sender&) = delete;
  void send(const std::string& bytes) const {
    ::sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&to_),
             sizeof to_);
  }

 private:
  int fd_;
  sockaddr_in to_{};
};

ubersim::sim_state_t state_with_robots() {
  ubersim::sim_state_t state{};
  for (int8_t team : {int8_t{ubersim::team_t::YELLOW}, int8_t{ubersim::team_t::BLUE}}) {
    for (int id = 0; id < 11; ++id) {
      ubersim::robot_state_t robot{};
      robot.team = team;
      robot.robot_id = id;
      robot.robot_type = "omni4_ssl";
      robot.last_command_time = -1;
      state.robots.push_back(robot);
    }
  }
  state.num_robots = static_cast<int32_t>(state.robots.size());
  return state;
}

// Stands in for physics and times the probes: robot 0 of the blue team.
class Harness {
 public:
  Harness(const std::string& url, int grsim_port)
      : bus_(ubersim::with_receive_buffer(url)), probe_(grsim_port), state_(state_with_robots()) {
    bus_.subscribe<ubersim::sim_commands_t>(
        "SIM_COMMANDS", [this](const ubersim::sim_commands_t& c) {
          if (c.team != ubersim::team_t::BLUE || waiting_ < 0) return;
          for (const auto& command : c.commands) {
            if (command.robot_id == 0 && std::abs(command.vx - waiting_) < 1e-4) {
              latencies_.push_back(std::chrono::duration<double>(Clock::now() - sent_).count());
              waiting_ = -1;
            }
          }
        });
  }
  // Runs the loop (states at 240 Hz) for `seconds`.
  void run_for(double seconds) {
    const auto end = Clock::now() + std::chrono::duration<double>(seconds);
    while (Clock::now() < end) step();
  }
  // `count` probes, one at a time, at least 20 ms apart; their latencies in s
  // (one not answered within 0.25 s is left out and shows in the count).
  std::vector<double> probe(int count) {
    latencies_.clear();
    for (int i = 0; i < count; ++i) {
      waiting_ = 0.5 + 0.001 * static_cast<double>(++probe_number_ % 400);
      sent_ = Clock::now();
      probe_.send(ubersim::test::grsim_forward_command(false, 0, static_cast<float>(waiting_)));
      // The next probe after this one's answer (at most 0.25 s) and 20 ms.
      const auto next = sent_ + std::chrono::milliseconds(20);
      const auto give_up = sent_ + std::chrono::milliseconds(250);
      while (Clock::now() < give_up && (waiting_ >= 0 || Clock::now() < next)) step();
    }
    waiting_ = -1;
    return latencies_;
  }

 private:
  void step() {
    const auto now = Clock::now();
    if (now >= next_state_) {
      state_.sim_time += 1.0 / 240;
      ++state_.step;
      bus_.publish("SIM_STATE", state_);
      next_state_ = now + std::chrono::microseconds(4167);
    }
    bus_.wait_and_handle(1);
  }

  ubersim::MessageBus bus_;
  Sender probe_;
  ubersim::sim_state_t state_;
  Clock::time_point next_state_{};
  Clock::time_point sent_{};
  double waiting_ = -1;  // vx of the probe in flight
  int probe_number_ = 0;
  std::vector<double> latencies_;
};

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return NAN;
  std::sort(values.begin(), values.end());
  return values[static_cast<size_t>(p * static_cast<double>(values.size() - 1))];
}

// Floods robots 1..10 of both teams at `rate` until `stop`; returns the count sent.
long flood(int port, int rate, const std::atomic<bool>& stop) {
  Sender sender(port);
  std::vector<std::string> packets;
  for (int i = 0; i < 20; ++i) {
    packets.push_back(
        ubersim::test::grsim_forward_command(i % 2 == 1, static_cast<uint32_t>(1 + i % 10), 0.1f));
  }
  const auto start = Clock::now();
  long sent = 0;
  while (!stop) {
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    const auto due = static_cast<long>(elapsed * rate);
    while (sent < due) sender.send(packets[static_cast<size_t>(sent++) % packets.size()]);
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return sent;
}

std::vector<std::string> bridge_argv(const Options& o) {
  const auto port = [&o](int offset) { return std::to_string(o.base_port + offset); };
  return {UBERSIM_SSL_BRIDGE_EXE,
          "--lcm-url",
          o.lcm_url,
          "--control-port",
          port(0),
          "--blue-port",
          port(1),
          "--yellow-port",
          port(2),
          "--vision-port",
          port(3),
          "--referee-port",
          port(4),
          "--tracked-port",
          port(5),
          "--grsim-port",
          port(6),
          "--grsim-blue-status-port",
          port(7),
          "--grsim-yellow-status-port",
          port(8),
          "-q"};
}

int run(const Options& o) {
  ubersim::test::TempFolder folder("grsim_bench");
  const std::string dir = folder.root().string();
  ubersim::ChildProcess bridge(bridge_argv(o), dir + "/grsim_bench_bridge.log");
  ubersim::ChildProcess radio({UBERSIM_RADIO_EXE, "--lcm-url", o.lcm_url, "--profile", "ideal",
                               "--config-dir", UBERSIM_CONFIG_DIR, "-q"},
                              dir + "/grsim_bench_radio.log");
  Harness harness(o.lcm_url, o.base_port + 6);
  harness.run_for(1.0);  // both subscribed, the radio has robots on the field
  harness.probe(10);     // warm-up

  const double bridge_quiet0 = cpu_seconds(bridge.pid()), radio_quiet0 = cpu_seconds(radio.pid());
  const auto quiet_start = Clock::now();
  const std::vector<double> quiet = harness.probe(o.probes);
  const double quiet_seconds = std::chrono::duration<double>(Clock::now() - quiet_start).count();
  const double bridge_quiet = cpu_seconds(bridge.pid()) - bridge_quiet0;
  const double radio_quiet = cpu_seconds(radio.pid()) - radio_quiet0;

  std::atomic<bool> stop{false};
  long sent = 0;
  const double bridge0 = cpu_seconds(bridge.pid()), radio0 = cpu_seconds(radio.pid());
  const auto start = Clock::now();
  std::thread flooder([&] { sent = flood(o.base_port + 6, o.rate, stop); });
  harness.run_for(0.5);
  std::vector<double> flooded = harness.probe(o.probes);
  const double rest = o.seconds - std::chrono::duration<double>(Clock::now() - start).count();
  if (rest > 0) harness.run_for(rest);
  stop = true;
  flooder.join();
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  const double bridge_cpu = cpu_seconds(bridge.pid()) - bridge0;
  const double radio_cpu = cpu_seconds(radio.pid()) - radio0;
  bridge.stop(5);
  radio.stop(5);
  folder.succeeded();

  std::printf("grSim flood: %ld packets in %.2f s (%.0f/s; asked %d/s)\n", sent, wall,
              static_cast<double>(sent) / wall, o.rate);
  std::printf("CPU per 10,000 grSim packets: bridge %.1f ms, radio emulator %.1f ms\n",
              1e3 * bridge_cpu / static_cast<double>(sent) * 1e4,
              1e3 * radio_cpu / static_cast<double>(sent) * 1e4);
  std::printf(
      "CPU share of one core: bridge %.3f quiet, %.3f flooded (x%.1f); radio %.3f quiet, "
      "%.3f flooded (x%.1f)\n",
      bridge_quiet / quiet_seconds, bridge_cpu / wall,
      (bridge_cpu / wall) / std::max(1e-9, bridge_quiet / quiet_seconds),
      radio_quiet / quiet_seconds, radio_cpu / wall,
      (radio_cpu / wall) / std::max(1e-9, radio_quiet / quiet_seconds));
  std::printf(
      "latency packet -> SIM_COMMANDS (ms): quiet median %.3f p95 %.3f (%zu/%d); flooded "
      "median %.3f p95 %.3f (%zu/%d); ratio flooded/quiet median %.2f, p95 %.2f\n",
      1e3 * percentile(quiet, 0.5), 1e3 * percentile(quiet, 0.95), quiet.size(), o.probes,
      1e3 * percentile(flooded, 0.5), 1e3 * percentile(flooded, 0.95), flooded.size(), o.probes,
      percentile(flooded, 0.5) / percentile(quiet, 0.5),
      percentile(flooded, 0.95) / percentile(quiet, 0.95));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_grsim_bench", [&] {
    Options o;
    CLI::App app{"CPU and command latency of grSim's protocol under a flood"};
    app.add_option("--lcm-url", o.lcm_url, "LCM URL of the bench's own processes")
        ->capture_default_str();
    app.add_option("--base-port", o.base_port, "the bridge's UDP ports: this .. this + 8")
        ->capture_default_str();
    app.add_option("--rate", o.rate, "flood packets per second")->capture_default_str();
    app.add_option("--seconds", o.seconds, "flood duration (s)")->capture_default_str();
    app.add_option("--probes", o.probes, "latency probes per phase")->capture_default_str();
    if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;
    return run(o);
  });
}
