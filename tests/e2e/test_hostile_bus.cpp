// The hostile bus (issue 13): the demo game runs while every input channel
// gets random datagrams, mutated real datagrams, one datagram per position
// with a 2^31-1 count written there, and a SIM_CONTROL request flood. Every
// process must stay alive, within 50 MB of its memory, back at its rates
// within 1 s, and stop on Ctrl-C. A second test floods SIM_COMMANDS at
// 20,000 datagrams/s and times physics' answers to PING.
// (This binary runs in its own network namespace: tests/run_isolated.sh.)
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <thread>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>

#include "e2e_support.hpp"
#include "ubersim/common_options.hpp"

using namespace e2e;
using ubersim::test::process_alive;
using Clock = std::chrono::steady_clock;

namespace {

// Every channel a process of the demo set reads from.
const std::vector<std::string> kInputChannels = {"RADIO_YELLOW", "RADIO_BLUE",     "SIM_COMMANDS",
                                                 "SIM_CONTROL",  "SIM_STATE",      "VISION",
                                                 "SIM_GEOMETRY", "VISION_GEOMETRY"};

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Resident memory of a process (MB), from /proc.
double resident_mb(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      double kb = 0;
      status >> kb;
      return kb / 1024;
    }
    status.ignore(1 << 12, '\n');
  }
  return -1;
}

// Real datagrams per channel, as the demo game sends them.
std::map<std::string, std::vector<std::vector<uint8_t>>> capture_real(ubersim::MessageBus& bus,
                                                                      double seconds) {
  std::map<std::string, std::vector<std::vector<uint8_t>>> real;
  bus.subscribe_raw(
      ".*", [&](const std::string& channel, const void* data, std::size_t size, std::int64_t) {
        auto& list = real[channel];
        if (list.size() < 50) {
          const auto* bytes = static_cast<const uint8_t*>(data);
          list.emplace_back(bytes, bytes + size);
        }
      });
  const auto start = Clock::now();
  while (seconds_since(start) < seconds) bus.wait_and_handle(20);
  return real;
}

// Sends at most `rate` datagrams per second.
class PacedSender {
 public:
  PacedSender(ubersim::MessageBus& bus, double rate) : bus_(bus), rate_(rate) {}
  void send(const std::string& channel, const std::vector<uint8_t>& bytes) {
    bus_.publish_encoded(channel, bytes.data(), bytes.size());
    ++sent_;
    const auto due = start_ + std::chrono::duration_cast<Clock::duration>(
                                  std::chrono::duration<double>(sent_ / rate_));
    if (due > Clock::now()) std::this_thread::sleep_until(due);
  }
  std::int64_t sent() const { return sent_; }

 private:
  ubersim::MessageBus& bus_;
  double rate_;
  Clock::time_point start_ = Clock::now();
  std::int64_t sent_ = 0;
};

std::vector<uint8_t> mutate(std::vector<uint8_t> bytes, std::mt19937& random) {
  std::uniform_int_distribution<int> kind(0, 4);
  std::uniform_int_distribution<int> byte(0, 255);
  if (bytes.empty()) bytes.push_back(0);
  std::uniform_int_distribution<std::size_t> at(0, bytes.size() - 1);
  switch (kind(random)) {
    case 0:  // flip a few bytes (past the fingerprint, so the walkers see them)
      for (int i = 0; i < 4; ++i) bytes[at(random)] = static_cast<uint8_t>(byte(random));
      break;
    case 1:  // truncate
      bytes.resize(at(random));
      break;
    case 2:  // extend
      for (int i = 0; i < 16; ++i) bytes.push_back(static_cast<uint8_t>(byte(random)));
      break;
    case 3:  // a large 4-byte value somewhere
      if (bytes.size() >= 4) {
        const std::size_t p = std::min(at(random), bytes.size() - 4);
        bytes[p] = static_cast<uint8_t>(byte(random) | 0x40);
      }
      break;
    default:  // a double's exponent turned into NaN / Inf territory
      bytes[at(random)] = 0x7f;
      if (bytes.size() > 1) bytes[at(random)] = 0xff;
      break;
  }
  return bytes;
}

struct Rates {
  int states = 0;
  int frames = 0;
  bool finite = true;
};

class RateListener {
 public:
  RateListener() : bus_(ubersim::with_receive_buffer(ubersim::default_lcm_url())) {
    bus_.subscribe<ubersim::sim_state_t>("SIM_STATE", [this](const ubersim::sim_state_t& s) {
      ++rates_.states;
      const auto finite = [](double v) { return std::isfinite(v); };
      rates_.finite = rates_.finite && finite(s.sim_time) && finite(s.ball.position[0]);
      for (const auto& r : s.robots) rates_.finite = rates_.finite && finite(r.x) && finite(r.y);
    });
    bus_.subscribe<ubersim::vision_frame_t>(
        "VISION", [this](const ubersim::vision_frame_t&) { ++rates_.frames; });
  }
  Rates window(double seconds) {
    rates_ = Rates{};
    const auto start = Clock::now();
    while (seconds_since(start) < seconds) bus_.wait_and_handle(10);
    return rates_;
  }

 private:
  ubersim::MessageBus bus_;
  Rates rates_;
};

void send_control(ubersim::MessageBus& bus, std::int8_t action, std::int64_t id, double speed = 1) {
  ubersim::sim_control_t request{};
  request.request_id = id;
  request.sender = "test_hostile_bus";
  request.action = action;
  request.speed_factor = speed;
  bus.publish("SIM_CONTROL", request);
}

}  // namespace

TEST(HostileBus, EveryProcessSurvivesAndRecovers) {
  TempDir dir;
  // Every step's state, so that 240 Hz tells physics is back at full pace.
  Launch launch({"--demo", "both", "--truth-every-step"}, dir);
  const auto pids = launch.processes();
  ASSERT_GE(pids.size(), 5u) << launch.output();

  ubersim::MessageBus attacker(ubersim::default_lcm_url());
  auto real = capture_real(attacker, 2.0);
  std::map<std::string, double> memory_before;
  for (const auto& [name, pid] : pids) memory_before[name] = resident_mb(pid);

  std::mt19937 random(13);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<int> length(0, 3000);
  PacedSender sender(attacker, 20000);
  const auto flood_start = Clock::now();
  for (const std::string& channel : kInputChannels) {
    const auto& samples = real[channel];
    // 2,000 random datagrams, half of them behind the channel's real fingerprint.
    for (int i = 0; i < 2000; ++i) {
      std::vector<uint8_t> bytes(static_cast<std::size_t>(length(random)));
      for (auto& b : bytes) b = static_cast<uint8_t>(byte(random));
      if (i % 2 == 0 && !samples.empty() && bytes.size() >= 8) {
        std::copy_n(samples[0].begin(), 8, bytes.begin());
      }
      sender.send(channel, bytes);
    }
    if (samples.empty()) continue;  // nobody sends on it in this game (a geometry channel)
    // 2,000 mutated real datagrams.
    for (int i = 0; i < 2000; ++i) {
      sender.send(channel, mutate(samples[static_cast<std::size_t>(i) % samples.size()], random));
    }
    // 2^31-1 written at every position past the fingerprint: every count field gets its turn.
    const auto& sample = samples.back();
    for (std::size_t at = 8; at + 4 <= sample.size(); ++at) {
      auto bytes = sample;
      bytes[at] = 0x7f;
      bytes[at + 1] = bytes[at + 2] = bytes[at + 3] = 0xff;
      sender.send(channel, bytes);
    }
  }
  // SIM_CONTROL at 100 times a referee's rate (PINGs at 1000/s for 2 s).
  for (int i = 0; i < 2000; ++i) {
    ubersim::sim_control_t ping{};
    ping.request_id = 1000000 + i;
    ping.sender = "flood";
    ping.action = ubersim::sim_control_t::PING;
    std::vector<uint8_t> bytes(static_cast<std::size_t>(ping.getEncodedSize()));
    ping.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    sender.send("SIM_CONTROL", bytes);
    std::this_thread::sleep_for(std::chrono::microseconds(950));
  }
  const double flood_seconds = seconds_since(flood_start);

  // Mutated SIM_CONTROL requests are well-formed requests too (pause, speed,
  // setup): a user would set the game going again, and so does the test.
  send_control(attacker, ubersim::sim_control_t::RESUME, 1);
  send_control(attacker, ubersim::sim_control_t::SET_SPEED, 2, 1.0);
  send_control(attacker, ubersim::sim_control_t::RESET, 3);

  RateListener listener;
  listener.window(1.0);  // the second after the flood: the time allowed to recover
  const Rates rates = listener.window(1.0);
  std::printf(
      "flood: %lld datagrams in %.1f s on %zu channels; after 1 s: SIM_STATE %d Hz, "
      "VISION %d frames/s\n",
      static_cast<long long>(sender.sent()), flood_seconds, kInputChannels.size(), rates.states,
      rates.frames);
  for (const auto& [name, pid] : pids) {
    EXPECT_TRUE(process_alive(pid)) << name << " died\n" << launch.output();
    const double after = resident_mb(pid);
    std::printf("  %-14s resident %.1f MB -> %.1f MB\n", name.c_str(), memory_before[name], after);
    EXPECT_LT(after - memory_before[name], 50.0) << name;
  }
  EXPECT_NEAR(rates.states, 240, 24) << "SIM_STATE not back at 240 Hz";
  EXPECT_TRUE(rates.finite) << "SIM_STATE carried a non-finite value";
  EXPECT_GT(rates.frames, 20) << "VISION not back";

  const auto stop_start = Clock::now();
  launch.script().stop(5, SIGINT);
  const double stop_seconds = seconds_since(stop_start);
  std::printf("Ctrl-C stopped everything in %.2f s\n", stop_seconds);
  EXPECT_LT(stop_seconds, 3.0);
  for (const auto& [name, pid] : pids) EXPECT_FALSE(process_alive(pid)) << name << " left behind";
}

TEST(HostileBus, PhysicsAnswersPingWhileItsCommandChannelIsFlooded) {
  TempDir dir;
  Launch launch({"--demo", "both"}, dir);
  const auto pids = launch.processes();
  // The acknowledgements come on the group the flood fills at 8 MB/s: with
  // the kernel's default 208 KB receive buffer, 25 ms without the CPU (a busy
  // machine) lose them in this test process, not in physics. Every process of
  // the simulator asks for 4 MB; so does the test.
  ubersim::MessageBus bus(ubersim::with_receive_buffer(ubersim::default_lcm_url()));
  auto real = capture_real(bus, 1.0);
  ASSERT_FALSE(real["SIM_COMMANDS"].empty()) << launch.output();
  const auto command = real["SIM_COMMANDS"].back();

  std::atomic<bool> flooding{true};
  std::int64_t flood_sent = 0;
  std::thread flood([&] {
    ubersim::MessageBus flood_bus(ubersim::default_lcm_url());
    PacedSender sender(flood_bus, 20000);
    std::mt19937 random(7);
    while (flooding) sender.send("SIM_COMMANDS", mutate(command, random));
    flood_sent = sender.sent();
  });

  std::map<std::int64_t, Clock::time_point> sent_at;
  std::vector<double> latencies_ms;
  std::string last_reply;
  bus.subscribe<ubersim::sim_control_ack_t>(
      "SIM_CONTROL_ACK", [&](const ubersim::sim_control_ack_t& ack) {
        const auto found = sent_at.find(ack.request_id);
        if (found == sent_at.end()) return;
        latencies_ms.push_back(1e3 * seconds_since(found->second));
        last_reply = ack.message;
        sent_at.erase(found);
      });
  const auto start = Clock::now();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the flood under way
  for (int i = 0; i < 30; ++i) {
    sent_at[i + 1] = Clock::now();
    send_control(bus, ubersim::sim_control_t::PING, i + 1);
    const auto next = Clock::now() + std::chrono::milliseconds(100);
    while (Clock::now() < next) bus.wait_until_and_handle(next);
  }
  const auto settle = Clock::now() + std::chrono::milliseconds(500);
  while (Clock::now() < settle) bus.wait_until_and_handle(settle);
  flooding = false;
  flood.join();
  const double flood_rate = static_cast<double>(flood_sent) / seconds_since(start);

  std::sort(latencies_ms.begin(), latencies_ms.end());
  ASSERT_EQ(latencies_ms.size(), 30u) << "pings unanswered: " << sent_at.size();
  std::printf(
      "SIM_COMMANDS flood %.0f datagrams/s: PING answered in median %.2f ms, max %.2f ms\n"
      "  physics' status reply: %s\n",
      flood_rate, latencies_ms[15], latencies_ms.back(), last_reply.c_str());
  EXPECT_GT(flood_rate, 15000.0);
  // The bound is 100 ms; a CI machine shared with other jobs can
  // deschedule physics for longer than that once, so one outlier may reach 0.5 s.
  EXPECT_LT(latencies_ms[28], 100.0);
  EXPECT_LT(latencies_ms.back(), 500.0);
  EXPECT_NE(last_reply.find("decode:SIM_COMMANDS="), std::string::npos)
      << "the status reply should count the dropped commands";
  for (const auto& [name, pid] : pids) EXPECT_TRUE(process_alive(pid)) << name;
  launch.script().stop(5, SIGINT);
}
