#pragma once
// SIM_CONTROL requests that several programs send alike, built in one place.
#include <cstdint>
#include <string>
#include <ubersim/sim_control_t.hpp>
#include <utility>

namespace ubersim {

// Asks physics to publish the field (SIM_GEOMETRY) now rather than at its next
// periodic one; every other field zero.
inline sim_control_t geometry_request(std::string sender, std::int64_t request_id) {
  sim_control_t request{};
  request.request_id = request_id;
  request.sender = std::move(sender);
  request.action = sim_control_t::REQUEST_GEOMETRY;
  return request;
}

}  // namespace ubersim
