#include "ubersim/referee/sim_link.hpp"

#include <unistd.h>

#include <algorithm>

#include "ubersim/sim_control_requests.hpp"
#include "ubersim/topics.hpp"

namespace ubersim::referee {

SimLink::SimLink(MessageBus& bus, ChannelNames channels, std::string sender)
    : bus_(bus),
      channels_(std::move(channels)),
      sender_(std::move(sender)),
      // Unique enough across concurrent referee invocations: pid and clock.
      next_request_id_((static_cast<std::int64_t>(::getpid()) << 32) ^
                       std::chrono::steady_clock::now().time_since_epoch().count()) {
  ubersim::subscribe(bus_, channels_, topics::kSimControlAck, [this](const sim_control_ack_t& ack) {
    if (ack.request_id == awaited_id_) ack_ = ack;
  });
  ubersim::subscribe(
      bus_, channels_, topics::kSimState, [this](const sim_state_t& state) { state_ = state; }, 4);
  ubersim::subscribe(bus_, channels_, topics::kSimGeometry,
                     [this](const field_geometry_t& g) { geometry_ = g; });
}

template <class Predicate>
void SimLink::wait_until(Predicate done, std::chrono::milliseconds timeout,
                         const std::string& what) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      throw NoAnswer("no answer from the physics server within " +
                     std::to_string(timeout.count() / 1000.0).substr(0, 4) + " s (" + what +
                     "): is ubersim_physics running on this LCM URL and channel prefix?");
    }
    bus_.wait_and_handle(static_cast<int>(std::min<long>(left.count(), 50)));
  }
}

sim_control_ack_t SimLink::request(sim_control_t control, std::chrono::milliseconds timeout) {
  control.request_id = next_request_id_++;
  control.sender = sender_;
  awaited_id_ = control.request_id;
  ack_.reset();
  ubersim::publish(bus_, channels_, topics::kSimControl, control);
  wait_until([this] { return ack_.has_value(); }, timeout,
             "waiting on " + channel_name(channels_, topics::kSimControlAck));
  return *ack_;
}

sim_state_t SimLink::state(std::chrono::milliseconds timeout) {
  state_.reset();
  wait_until([this] { return state_.has_value(); }, timeout,
             "waiting on " + channel_name(channels_, topics::kSimState));
  return *state_;
}

field_geometry_t SimLink::geometry(std::chrono::milliseconds timeout) {
  // Asked again every half second: a physics server still starting up (the
  // automatic referee may start alongside it) has not subscribed yet and
  // loses the request; it also publishes the geometry by itself now and then.
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!geometry_) {
    ubersim::publish(bus_, channels_, topics::kSimControl,
                     geometry_request(sender_, next_request_id_++));
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    try {
      wait_until([this] { return geometry_.has_value(); },
                 std::min(left, std::chrono::milliseconds(500)),
                 "waiting on " + channel_name(channels_, topics::kSimGeometry));
    } catch (const NoAnswer&) {
      if (std::chrono::steady_clock::now() >= deadline) throw;
    }
  }
  return *geometry_;
}

}  // namespace ubersim::referee
