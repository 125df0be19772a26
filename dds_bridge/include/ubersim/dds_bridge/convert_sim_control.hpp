#pragma once
// SIM_CONTROL: sim_control_t <-> SimControl_; SIM_CONTROL_ACK:
// sim_control_ack_t <-> SimControlAck_. LCM booleans (int8) become DDS booleans.
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/sim_control_t.hpp>

#include "ubersim/dds_bridge/dds_sample.hpp"

namespace ubersim::dds {

OwnedSample<DdsSimControl> to_dds(const sim_control_t& control);
sim_control_t from_dds(const DdsSimControl& control);

OwnedSample<DdsSimControlAck> to_dds(const sim_control_ack_t& ack);
sim_control_ack_t from_dds(const DdsSimControlAck& ack);

}  // namespace ubersim::dds
