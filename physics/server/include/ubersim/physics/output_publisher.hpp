#pragma once
// Puts what PhysicsCore returned on the bus, in its order: SIM_STATE,
// SIM_GEOMETRY, SIM_CONTROL_ACK (typed topics, topics.hpp).
#include <cstdint>
#include <string>
#include <ubersim/field_geometry_t.hpp>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/physics/physics_core.hpp"

namespace ubersim::physics {

class OutputPublisher {
 public:
  // `channels` must outlive the publisher (the host's do).
  OutputPublisher(MessageBus& bus, const ChannelNames& channels);

  void publish(const PhysicsCore::Output& out);
  void publish_geometry(const field_geometry_t& geometry);

 private:
  MessageBus& bus_;
  const ChannelNames& channels_;
  std::string state_channel_;
  // SIM_STATE is encoded into this buffer, kept across steps: LCM's own
  // publish allocates one every time, tens of thousands of times a second.
  std::vector<std::uint8_t> state_buffer_;
};

}  // namespace ubersim::physics
