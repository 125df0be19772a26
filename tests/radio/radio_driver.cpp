#include "radio_driver.hpp"

#include <chrono>

#include "radio_test_util.hpp"
#include "ubersim/common_options.hpp"
#include "ubersim/topics.hpp"

namespace radio_test {

RadioDriver::RadioDriver(int robots_per_team)
    : bus_(ubersim::with_receive_buffer(ubersim::default_lcm_url())),
      robots_per_team_(robots_per_team) {
  ubersim::subscribe(bus_, channels_, ubersim::topics::kSimCommands,
                     [this](const ubersim::sim_commands_t& m) {
                       if (m.team == 1 && m.sequence < 0) {  // a ping coming back
                         last_ping_back_ = -m.sequence;
                         return;
                       }
                       if (m.team == 0 || m.team == 1) commands_[m.team].push_back(m);
                     });
  for (int team = 0; team < 2; ++team) {
    bus_.subscribe<ubersim::radio_feedback_t>(
        ubersim::channel_name(channels_,
                              ubersim::topics::kRadioFeedback.of(static_cast<ubersim::Team>(team))),
        [this, team](const ubersim::radio_feedback_t& m) {
          feedback_[team].push_back({m, last_state_time_});
        });
  }
}

void RadioDriver::publish_state(std::int64_t step) {
  auto s = state(step * kStep, step, robots_per_team_);
  if (decorate) decorate(s);
  last_state_time_ = s.sim_time;
  ubersim::publish(bus_, channels_, ubersim::topics::kSimState, s);
}

void RadioDriver::send(int team, const ubersim::radio_packet_t& p) {
  ubersim::publish(bus_, channels_, ubersim::topics::kRadio.of(static_cast<ubersim::Team>(team)),
                   p);
}

void RadioDriver::publish_raw(const std::string& channel, const std::vector<std::uint8_t>& bytes) {
  bus_.publish_encoded(channel, bytes.data(), bytes.size());
}

bool RadioDriver::wait_for_ping(std::int64_t id, int timeout_ms) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  while (last_ping_back_ < id) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    bus_.wait_and_handle(static_cast<int>(left.count()));
  }
  return true;
}

bool RadioDriver::sync(int timeout_ms) {
  const std::int64_t id = ++pings_sent_;
  send(1, packet(1, -id, {0}));
  return wait_for_ping(id, timeout_ms);
}

bool RadioDriver::wait_ready(int timeout_ms) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  while (std::chrono::steady_clock::now() < deadline) {
    publish_state(0);
    if (sync(100)) return true;
  }
  return false;
}

}  // namespace radio_test
