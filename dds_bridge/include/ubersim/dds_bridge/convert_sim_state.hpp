#pragma once
// SIM_STATE: sim_state_t <-> SimState_ (robots with their body state and wheel
// speeds, the ball). LCM booleans (int8) become DDS booleans.
#include <ubersim/sim_state_t.hpp>

#include "ubersim/dds_bridge/dds_sample.hpp"

namespace ubersim::dds {

OwnedSample<DdsSimState> to_dds(const sim_state_t& state);
sim_state_t from_dds(const DdsSimState& state);

}  // namespace ubersim::dds
