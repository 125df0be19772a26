#include "ubersim/truth_demand_announcer.hpp"

namespace ubersim {

TruthDemandAnnouncer::TruthDemandAnnouncer(MessageBus& bus, const ChannelNames& channels,
                                           std::string consumer)
    : bus_(bus), channel_(channels.extra(kTruthDemandChannel)) {
  demand_.consumer = std::move(consumer);
}

void TruthDemandAnnouncer::every_step() {
  demand_.every_step = true;
  demand_.num_periodic = 0;
  demand_.period.clear();
  demand_.phase.clear();
  asking_ = changed_ = true;
}

void TruthDemandAnnouncer::periodic(double rate_hz) {
  demand_.every_step = false;
  demand_.num_periodic = 1;
  demand_.period = {1.0 / rate_hz};
  demand_.phase = {0.0};
  asking_ = changed_ = true;
}

void TruthDemandAnnouncer::nothing() {
  asking_ = changed_ = false;
}

void TruthDemandAnnouncer::tick(Clock::time_point now) {
  if (!asking_ || (!changed_ && now < next_)) return;
  announce(now);
}

void TruthDemandAnnouncer::announce(Clock::time_point now) {
  if (!asking_) return;
  bus_.publish(channel_, demand_);
  changed_ = false;
  next_ = now + kRepeat;
}

}  // namespace ubersim
