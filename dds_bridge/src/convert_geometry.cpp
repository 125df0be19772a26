#include "ubersim/dds_bridge/convert_geometry.hpp"

#include <algorithm>
#include <iterator>

namespace ubersim::dds {
namespace {

// Fills `to` (zeroed, owned by a sample) from `from`; used alone and nested.
void field_to_dds(const field_geometry_t& from, DdsFieldGeometry& to) {
  to.name = dds_string(from.name);
  to.field_length = from.field_length;
  to.field_width = from.field_width;
  to.boundary_width = from.boundary_width;
  to.line_width = from.line_width;
  to.goal_width = from.goal_width;
  to.goal_depth = from.goal_depth;
  to.goal_height = from.goal_height;
  to.goal_wall_thickness = from.goal_wall_thickness;
  to.wall_height = from.wall_height;
  to.wall_thickness = from.wall_thickness;
  to.center_circle_radius = from.center_circle_radius;
  to.penalty_area_depth = from.penalty_area_depth;
  to.penalty_area_width = from.penalty_area_width;
  to.ball_radius = from.ball_radius;
  to.penalty_mark_distance = from.penalty_mark_distance;
  to.boundary_width_goal_line = from.boundary_width_goal_line;
  to.goal_substitution_area_width = from.goal_substitution_area_width;
}

field_geometry_t field_from_dds(const DdsFieldGeometry& from) {
  field_geometry_t to{};
  to.name = from_dds_string(from.name);
  to.field_length = from.field_length;
  to.field_width = from.field_width;
  to.boundary_width = from.boundary_width;
  to.line_width = from.line_width;
  to.goal_width = from.goal_width;
  to.goal_depth = from.goal_depth;
  to.goal_height = from.goal_height;
  to.goal_wall_thickness = from.goal_wall_thickness;
  to.wall_height = from.wall_height;
  to.wall_thickness = from.wall_thickness;
  to.center_circle_radius = from.center_circle_radius;
  to.penalty_area_depth = from.penalty_area_depth;
  to.penalty_area_width = from.penalty_area_width;
  to.ball_radius = from.ball_radius;
  to.penalty_mark_distance = from.penalty_mark_distance;
  to.boundary_width_goal_line = from.boundary_width_goal_line;
  to.goal_substitution_area_width = from.goal_substitution_area_width;
  return to;
}

void camera_to_dds(const camera_calibration_t& from, DdsCameraCalibration& to) {
  to.camera_id = from.camera_id;
  to.focal_length = from.focal_length;
  to.principal_x = from.principal_x;
  to.principal_y = from.principal_y;
  to.image_width = from.image_width;
  to.image_height = from.image_height;
  std::copy(std::begin(from.position), std::end(from.position), std::begin(to.position));
  std::copy(std::begin(from.orientation), std::end(from.orientation), std::begin(to.orientation));
  to.distortion = from.distortion;
}

camera_calibration_t camera_from_dds(const DdsCameraCalibration& from) {
  camera_calibration_t to{};
  to.camera_id = from.camera_id;
  to.focal_length = from.focal_length;
  to.principal_x = from.principal_x;
  to.principal_y = from.principal_y;
  to.image_width = from.image_width;
  to.image_height = from.image_height;
  std::copy(std::begin(from.position), std::end(from.position), std::begin(to.position));
  std::copy(std::begin(from.orientation), std::end(from.orientation), std::begin(to.orientation));
  to.distortion = from.distortion;
  return to;
}

}  // namespace

OwnedSample<DdsFieldGeometry> to_dds(const field_geometry_t& field) {
  OwnedSample<DdsFieldGeometry> sample;
  field_to_dds(field, sample.get());
  return sample;
}

field_geometry_t from_dds(const DdsFieldGeometry& field) {
  return field_from_dds(field);
}

OwnedSample<DdsVisionGeometry> to_dds(const vision_geometry_t& geometry) {
  OwnedSample<DdsVisionGeometry> sample;
  DdsVisionGeometry& to = sample.get();
  to.t_sent = geometry.t_sent;
  field_to_dds(geometry.field, to.field);
  fill_sequence(to.cameras, geometry.cameras, camera_to_dds);
  return sample;
}

vision_geometry_t from_dds(const DdsVisionGeometry& geometry) {
  vision_geometry_t to{};
  to.t_sent = geometry.t_sent;
  to.field = field_from_dds(geometry.field);
  to.cameras = from_dds_sequence<camera_calibration_t>(geometry.cameras, camera_from_dds);
  to.num_cameras = count_of(to.cameras);
  return to;
}

}  // namespace ubersim::dds
