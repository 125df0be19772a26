#pragma once
// What a consumer of ground truth tells physics it needs (docs/sync.md,
// "Ground truth on demand"): a truth_demand_t on SIM_TRUTH_DEMAND, sent when it
// changes and again at least once a second (physics forgets a consumer not
// heard for 3 s). Call tick() from the process's loop, as often as it wakes.
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <ubersim/truth_demand_t.hpp>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/message_bus.hpp"

namespace ubersim {

class TruthDemandAnnouncer {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::milliseconds kRepeat{1000};

  TruthDemandAnnouncer(MessageBus& bus, const ChannelNames& channels, std::string consumer);

  // What is asked for from now on (sent at the next tick).
  void every_step();
  void periodic(double rate_hz);  // instants n / rate of sim time
  void nothing();                 // stop asking (no message: physics forgets in 3 s)

  // A demand a core computes (instants ahead of its frames, feedback samples):
  // from now on the demand is `source()`, asked again whenever it is sent.
  // OnChange: each tick asks the source and sends the demand when its bytes
  // differ from the last sent. OnAnnounce: sent only by announce() (the
  // program decides when its demand runs low). In both it goes out again,
  // as the source says then, once kRepeat has passed since it last went out.
  enum class Renewal { OnChange, OnAnnounce };
  void follow(std::function<truth_demand_t()> source, Renewal renewal);

  // Sends the demand if it changed or kRepeat has passed since it was last sent.
  void tick(Clock::time_point now = Clock::now());
  // Sends the demand now (if there is one), e.g. before a sync registration
  // that lets physics start stepping: it must know the demand from step one.
  void announce(Clock::time_point now = Clock::now());

 private:
  MessageBus& bus_;
  std::string channel_;
  truth_demand_t demand_{};
  void send(Clock::time_point now);

  std::function<truth_demand_t()> source_;
  Renewal renewal_ = Renewal::OnAnnounce;
  // The last demand sent, encoded, and the next one (buffers kept across ticks).
  std::vector<std::uint8_t> sent_bytes_, bytes_;
  bool asking_ = false;
  bool changed_ = false;
  Clock::time_point next_{};
};

}  // namespace ubersim
