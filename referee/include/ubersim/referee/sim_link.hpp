#pragma once
// The referee's line to the physics server: send a sim_control_t and wait for
// its acknowledgement; fetch the current ground truth and field geometry.
// Every wait has a timeout so a missing physics server is a clear error.
#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>

#include "ubersim/channels.hpp"
#include "ubersim/message_bus.hpp"

namespace ubersim::referee {

class NoAnswer : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class SimLink {
 public:
  SimLink(MessageBus& bus, ChannelNames channels, std::string sender);

  // Fills request_id and sender, publishes, waits for the matching ack.
  sim_control_ack_t request(sim_control_t control, std::chrono::milliseconds timeout);
  // The next SIM_STATE to arrive.
  sim_state_t state(std::chrono::milliseconds timeout);
  // Field geometry (asks physics for it if none arrives by itself).
  field_geometry_t geometry(std::chrono::milliseconds timeout);

 private:
  template <class Predicate>
  void wait_until(Predicate done, std::chrono::milliseconds timeout, const std::string& what);

  MessageBus& bus_;
  ChannelNames channels_;
  std::string sender_;
  std::int64_t next_request_id_;
  std::optional<sim_control_ack_t> ack_;
  std::int64_t awaited_id_ = -1;
  std::optional<sim_state_t> state_;
  std::optional<field_geometry_t> geometry_;
};

}  // namespace ubersim::referee
