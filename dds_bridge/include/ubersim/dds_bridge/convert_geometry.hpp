#pragma once
// SIM_GEOMETRY: field_geometry_t <-> FieldGeometry_;
// VISION_GEOMETRY: vision_geometry_t <-> VisionGeometry_ (field + camera calibrations).
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/vision_geometry_t.hpp>

#include "ubersim/dds_bridge/dds_sample.hpp"

namespace ubersim::dds {

OwnedSample<DdsFieldGeometry> to_dds(const field_geometry_t& field);
field_geometry_t from_dds(const DdsFieldGeometry& field);

OwnedSample<DdsVisionGeometry> to_dds(const vision_geometry_t& geometry);
vision_geometry_t from_dds(const DdsVisionGeometry& geometry);

}  // namespace ubersim::dds
