#include "ubersim/truth_demand_announcer.hpp"

#include "ubersim/topics.hpp"

namespace ubersim {

truth_demand_t every_step_demand() {
  truth_demand_t demand{};
  demand.every_step = true;
  return demand;
}

truth_demand_t periodic_demand(double rate_hz) {
  truth_demand_t demand{};
  demand.num_periodic = 1;
  demand.period = {1.0 / rate_hz};
  demand.phase = {0.0};
  return demand;
}

TruthDemandAnnouncer::TruthDemandAnnouncer(MessageBus& bus, const ChannelNames& channels,
                                           std::string consumer)
    : bus_(bus),
      channel_(channel_name(channels, topics::kTruthDemand)),
      consumer_(std::move(consumer)) {}

void TruthDemandAnnouncer::ask(Source source) {
  source_ = std::move(source);
  sent_any_ = false;  // a new demand goes out at the next tick
}

void TruthDemandAnnouncer::tick(Clock::time_point now) {
  if (!source_) return;
  encode_demand();
  if (!sent_any_ || bytes_ != sent_bytes_ || now >= next_) send(now);
}

void TruthDemandAnnouncer::send_now(Clock::time_point now) {
  if (!source_) return;
  encode_demand();
  send(now);
}

void TruthDemandAnnouncer::encode_demand() {
  demand_ = source_();
  if (demand_.consumer.empty()) demand_.consumer = consumer_;
  const auto size = static_cast<std::size_t>(demand_.getEncodedSize());
  bytes_.resize(size);
  demand_.encode(bytes_.data(), 0, static_cast<int>(size));
}

void TruthDemandAnnouncer::send(Clock::time_point now) {
  bus_.publish_encoded(channel_, bytes_.data(), bytes_.size());
  sent_bytes_.swap(bytes_);
  sent_any_ = true;
  next_ = now + kRepeat;
}

}  // namespace ubersim
