#include "lockstep_replay.hpp"

#include <algorithm>
#include <cmath>
#include <lcm/lcm-cpp.hpp>
#include <set>
#include <stdexcept>
#include <thread>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_commands_t.hpp>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/team_t.hpp>

#include "ubersim/bounded_decode.hpp"
#include "ubersim/common_options.hpp"

namespace e2e {
namespace {

constexpr double kReactionTime = 0.1;  // s after capture at which a packet is replayed
constexpr double kStepsPerSecond = 240.0;

struct RecordedPacket {
  double publish_time;
  std::string channel;
  ubersim::radio_packet_t packet;
};

std::vector<RecordedPacket> read_packets(const std::string& log_path, double until) {
  lcm::LogFile log(log_path, "r");
  if (!log.good()) throw std::runtime_error("cannot read " + log_path);
  std::vector<RecordedPacket> packets;
  while (const lcm::LogEvent* event = log.readNextEvent()) {
    if (event->channel != "RADIO_YELLOW" && event->channel != "RADIO_BLUE") continue;
    RecordedPacket recorded;
    if (!ubersim::decode_bounded(event->data, static_cast<std::size_t>(event->datalen),
                                 recorded.packet)) {
      continue;
    }
    recorded.channel = event->channel;
    recorded.publish_time = recorded.packet.t_sent + kReactionTime;
    if (recorded.publish_time < until) packets.push_back(recorded);
  }
  std::stable_sort(packets.begin(), packets.end(),
                   [](const auto& a, const auto& b) { return a.publish_time < b.publish_time; });
  return packets;
}

}  // namespace

ReplayResult replay_in_lockstep(const std::string& log_path, double until_sim_time,
                                const TempDir& dir, const std::string& run_name) {
  const auto packets = read_packets(log_path, until_sim_time);
  const std::string seed = "7";
  using ubersim::test::ChildProcess;
  // The emulators first, so they see physics' very first state and geometry.
  ChildProcess vision({bin_dir() + "/ubersim_vision", "--profile", "cmdragons02", "--seed", seed},
                      dir.path(run_name + "_vision.log"));
  ChildProcess radio({bin_dir() + "/ubersim_radio", "--profile",
                      source_dir() + "/tests/data/radio_lossless.cfg", "--seed", seed},
                     dir.path(run_name + "_radio.log"));
  // Both log these lines once subscribed (vision: just before; allow for it).
  if (!radio.wait_for_output("sim time from", 10) || !vision.wait_for_output("subscribing", 10)) {
    throw std::runtime_error("emulators did not start: " + radio.log() + vision.log());
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  ChildProcess physics({bin_dir() + "/ubersim_physics", "--lockstep", "--seed", seed, "--scenario",
                        "division_b_6v6"},
                       dir.path(run_name + "_physics.log"));

  ubersim::MessageBus bus(ubersim::with_receive_buffer(ubersim::default_lcm_url()));
  ReplayResult result;
  std::set<std::pair<int, int64_t>> forwarded;
  std::int64_t awaited_ack = -1;
  bool acked = false;
  bus.subscribe<ubersim::vision_frame_t>(
      "VISION", [&](const ubersim::vision_frame_t& f) { result.frames.push_back(encode(f)); });
  bus.subscribe<ubersim::sim_commands_t>("SIM_COMMANDS", [&](const ubersim::sim_commands_t& c) {
    forwarded.insert({c.team, c.sequence});
  });
  bus.subscribe<ubersim::sim_control_ack_t>("SIM_CONTROL_ACK",
                                            [&](const ubersim::sim_control_ack_t& ack) {
                                              if (ack.request_id == awaited_ack) acked = true;
                                            });
  auto wait = [&](const std::function<bool()>& done, double timeout_s) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (!done() && std::chrono::steady_clock::now() < deadline) bus.wait_and_handle(10);
    return done();
  };
  std::int64_t request_id = 0;
  auto control = [&](int8_t action, int32_t steps) {
    ubersim::sim_control_t request{};
    request.request_id = awaited_ack = ++request_id;
    request.sender = "lockstep_replay";
    request.action = action;
    request.step_count = steps;
    acked = false;
    bus.publish("SIM_CONTROL", request);
    if (!wait([&] { return acked; }, 30)) throw std::runtime_error("physics did not acknowledge");
  };

  // Ready: physics answers, and the vision emulator has its field geometry.
  for (int i = 0; i < 50 && !acked; ++i) {
    ubersim::sim_control_t ping{};
    ping.request_id = awaited_ack = ++request_id;
    ping.action = ubersim::sim_control_t::PING;
    bus.publish("SIM_CONTROL", ping);
    wait([&] { return acked; }, 0.2);
  }
  if (!acked) throw std::runtime_error("physics did not answer: " + physics.log());
  if (!vision.wait_for_output("field '", 10))
    throw std::runtime_error("no geometry: " + vision.log());

  std::int64_t step = 0;
  auto step_to = [&](double sim_time) {
    const auto target = static_cast<std::int64_t>(std::ceil(sim_time * kStepsPerSecond - 1e-9));
    if (target > step) control(ubersim::sim_control_t::STEP, static_cast<int32_t>(target - step));
    step = std::max(step, target);
  };
  for (const auto& recorded : packets) {
    step_to(recorded.publish_time);
    bus.publish(recorded.channel, recorded.packet);
    ++result.packets_replayed;
    const std::pair<int, int64_t> key{recorded.packet.team, recorded.packet.sequence};
    if (!wait([&] { return forwarded.count(key) != 0; }, 5)) ++result.packets_not_forwarded;
  }
  step_to(until_sim_time);
  // Let the vision emulator publish what the last states released.
  std::size_t seen = 0;
  do {
    seen = result.frames.size();
    wait([] { return false; }, 0.3);
  } while (result.frames.size() != seen);
  physics.stop();
  vision.stop();
  radio.stop();
  return result;
}

}  // namespace e2e
