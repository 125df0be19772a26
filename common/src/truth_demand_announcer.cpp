#include "ubersim/truth_demand_announcer.hpp"

#include "ubersim/topics.hpp"

namespace ubersim {

TruthDemandAnnouncer::TruthDemandAnnouncer(MessageBus& bus, const ChannelNames& channels,
                                           std::string consumer)
    : bus_(bus), channel_(channel_name(channels, topics::kTruthDemand)) {
  demand_.consumer = std::move(consumer);
}

void TruthDemandAnnouncer::every_step() {
  source_ = nullptr;
  demand_.every_step = true;
  demand_.num_periodic = 0;
  demand_.period.clear();
  demand_.phase.clear();
  asking_ = changed_ = true;
}

void TruthDemandAnnouncer::periodic(double rate_hz) {
  source_ = nullptr;
  demand_.every_step = false;
  demand_.num_periodic = 1;
  demand_.period = {1.0 / rate_hz};
  demand_.phase = {0.0};
  asking_ = changed_ = true;
}

void TruthDemandAnnouncer::nothing() {
  source_ = nullptr;
  asking_ = changed_ = false;
}

void TruthDemandAnnouncer::follow(std::function<truth_demand_t()> source, Renewal renewal) {
  source_ = std::move(source);
  renewal_ = renewal;
  asking_ = true;
  changed_ = false;
}

void TruthDemandAnnouncer::tick(Clock::time_point now) {
  if (!asking_) return;
  if (source_ && renewal_ == Renewal::OnChange && now < next_) {
    // Compared as encoded bytes: no allocation per tick once the buffers grew.
    demand_ = source_();
    const auto size = static_cast<std::size_t>(demand_.getEncodedSize());
    bytes_.resize(size);
    demand_.encode(bytes_.data(), 0, static_cast<int>(size));
    if (bytes_ != sent_bytes_) send(now);
    return;
  }
  if (!changed_ && now < next_) return;
  announce(now);
}

void TruthDemandAnnouncer::announce(Clock::time_point now) {
  if (!asking_) return;
  if (source_) {
    demand_ = source_();
    const auto size = static_cast<std::size_t>(demand_.getEncodedSize());
    bytes_.resize(size);
    demand_.encode(bytes_.data(), 0, static_cast<int>(size));
  }
  send(now);
}

void TruthDemandAnnouncer::send(Clock::time_point now) {
  if (source_) {
    bus_.publish_encoded(channel_, bytes_.data(), bytes_.size());
    sent_bytes_.swap(bytes_);
  } else {
    bus_.publish(channel_, demand_);
  }
  changed_ = false;
  next_ = now + kRepeat;
}

}  // namespace ubersim
