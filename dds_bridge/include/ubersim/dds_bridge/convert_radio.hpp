#pragma once
// RADIO_<TEAM>: radio_packet_t <-> RadioPacket_; RADIO_FEEDBACK_<TEAM>:
// radio_feedback_t <-> RadioFeedback_; SIM_COMMANDS: sim_commands_t <-> SimCommands_.
// LCM's `sequence` field is `sequence_number` in IDL (a keyword there).
// LCM booleans (int8) become DDS booleans: any non-zero value reads back as 1.
#include <ubersim/radio_feedback_t.hpp>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_commands_t.hpp>

#include "ubersim/dds_bridge/dds_sample.hpp"

namespace ubersim::dds {

OwnedSample<DdsRadioPacket> to_dds(const radio_packet_t& packet);
radio_packet_t from_dds(const DdsRadioPacket& packet);

OwnedSample<DdsRadioFeedback> to_dds(const radio_feedback_t& feedback);
radio_feedback_t from_dds(const DdsRadioFeedback& feedback);

OwnedSample<DdsSimCommands> to_dds(const sim_commands_t& commands);
sim_commands_t from_dds(const DdsSimCommands& commands);

}  // namespace ubersim::dds
