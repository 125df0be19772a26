#pragma once
// VISION: ubersim vision_frame_t <-> ubersim_msgs::msg::dds_::VisionFrame_.
// Every field is carried unchanged; LCM's num_* counts are the sequence lengths.
#include <ubersim/vision_frame_t.hpp>

#include "ubersim/dds_bridge/dds_sample.hpp"

namespace ubersim::dds {

OwnedSample<DdsVisionFrame> to_dds(const vision_frame_t& frame);
vision_frame_t from_dds(const DdsVisionFrame& frame);

}  // namespace ubersim::dds
