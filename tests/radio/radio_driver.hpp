#pragma once
// Drives a real ubersim_radio process over real LCM the way physics and two
// teams' control software would, in sim time: it publishes SIM_STATE at 240 Hz
// of sim time and radio packets interleaved in a fixed pattern, and records
// SIM_COMMANDS and RADIO_FEEDBACK_*.
//
// Catching up: the emulator handles its messages in the order they were sent,
// so the driver pings it through the blue team's link (given a profile with no
// rate limit, latency or loss) and waits for the ping to come back on
// SIM_COMMANDS: everything sent before has then been handled. However slow the
// machine, the run is the same.
#include <cstdint>
#include <functional>
#include <string>
#include <ubersim/radio_feedback_t.hpp>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_commands_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/message_bus.hpp"

namespace radio_test {

struct ReceivedFeedback {
  ubersim::radio_feedback_t message;
  double last_state_published;  // the driver's latest SIM_STATE time when it arrived (s)
};

class RadioDriver {
 public:
  static constexpr double kStep = 1.0 / 240;  // s

  explicit RadioDriver(int robots_per_team);

  // Ground truth of step k (t = k * kStep), after `decorate` had its say.
  void publish_state(std::int64_t step);
  void send(int team, const ubersim::radio_packet_t& packet);
  void publish_raw(const std::string& channel, const std::vector<std::uint8_t>& bytes);
  // Waits until the emulator has handled everything sent so far.
  bool sync(int timeout_ms = 30000);
  // Waits until the emulator listens (publishing step-0 ground truth meanwhile).
  bool wait_ready(int timeout_ms = 30000);

  std::function<void(ubersim::sim_state_t&)> decorate;
  const std::vector<ubersim::sim_commands_t>& commands(int team) const { return commands_[team]; }
  const std::vector<ReceivedFeedback>& feedback(int team) const { return feedback_[team]; }
  double last_state_time() const { return last_state_time_; }
  const ubersim::ChannelNames& channels() const { return channels_; }

 private:
  bool wait_for_ping(std::int64_t id, int timeout_ms);

  ubersim::ChannelNames channels_;
  ubersim::MessageBus bus_;
  int robots_per_team_;
  double last_state_time_ = -1;
  std::int64_t pings_sent_ = 0;
  std::int64_t last_ping_back_ = 0;
  std::vector<ubersim::sim_commands_t> commands_[2];
  std::vector<ReceivedFeedback> feedback_[2];
};

}  // namespace radio_test
