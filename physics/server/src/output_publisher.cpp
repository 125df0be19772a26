#include "ubersim/physics/output_publisher.hpp"

#include "ubersim/topics.hpp"

namespace ubersim::physics {

OutputPublisher::OutputPublisher(MessageBus& bus, const ChannelNames& channels)
    : bus_(bus), channels_(channels), state_channel_(channel_name(channels, topics::kSimState)) {}

void OutputPublisher::publish(const PhysicsCore::Output& out) {
  for (const sim_state_t& state : out.states) {
    const auto size = static_cast<std::size_t>(state.getEncodedSize());
    if (state_buffer_.size() < size) state_buffer_.resize(size);
    state.encode(state_buffer_.data(), 0, static_cast<int>(size));
    bus_.publish_encoded(state_channel_, state_buffer_.data(), size);
  }
  if (out.geometry) ubersim::publish(bus_, channels_, topics::kSimGeometry, *out.geometry);
  if (out.ack) ubersim::publish(bus_, channels_, topics::kSimControlAck, *out.ack);
}

void OutputPublisher::publish_geometry(const field_geometry_t& geometry) {
  ubersim::publish(bus_, channels_, topics::kSimGeometry, geometry);
}

}  // namespace ubersim::physics
