#pragma once
// What a consumer of ground truth tells physics it needs (docs/sync.md,
// "Ground truth on demand"): a truth_demand_t on SIM_TRUTH_DEMAND. A program
// states it once, on its host (ProcessHost::ask_for_truth), as a function
// that says the demand whenever asked (a fixed one: every_step_demand(),
// periodic_demand()); this announcer, which the host ticks after every
// wakeup, sends it when it differs from what went out last and at least once
// a second (physics forgets a consumer not heard for 3 s).
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <ubersim/truth_demand_t.hpp>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/message_bus.hpp"

namespace ubersim {

// The state after every step.
truth_demand_t every_step_demand();
// The states at the instants n / rate_hz of sim time, n >= 0.
truth_demand_t periodic_demand(double rate_hz);

class TruthDemandAnnouncer {
 public:
  using Clock = std::chrono::steady_clock;
  // The demand as it stands (the consumer's name is filled in when empty).
  using Source = std::function<truth_demand_t()>;
  static constexpr std::chrono::milliseconds kRepeat{1000};

  TruthDemandAnnouncer(MessageBus& bus, const ChannelNames& channels, std::string consumer);

  // What is asked for from now on: sent at the next tick.
  void ask(Source source);
  // Sends the demand if it differs from the last sent or kRepeat has passed
  // since it went out.
  void tick(Clock::time_point now);
  // Sends the demand now, changed or not (if there is one): before something
  // that lets physics step (a sync registration), which must know it by then.
  void send_now(Clock::time_point now);

 private:
  // Asks the source and encodes its demand into bytes_.
  void encode_demand();
  void send(Clock::time_point now);

  MessageBus& bus_;
  std::string channel_;
  std::string consumer_;
  Source source_;
  truth_demand_t demand_{};
  // The last demand sent, encoded, and the next one (buffers kept across ticks,
  // so that comparing allocates nothing once they grew).
  std::vector<std::uint8_t> sent_bytes_, bytes_;
  bool sent_any_ = false;
  Clock::time_point next_{};
};

}  // namespace ubersim
