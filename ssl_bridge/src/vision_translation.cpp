#include "ubersim/ssl_bridge/vision_translation.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "ubersim/config.hpp"
#include "ubersim/config_paths.hpp"
#include "ubersim/ssl_bridge/units.hpp"

namespace ubersim::ssl {
namespace {

void fill_robot(const vision_robot_t& in, SSL_DetectionRobot& out) {
  out.set_confidence(in.confidence);
  out.set_robot_id(static_cast<uint32_t>(in.robot_id));
  out.set_x(static_cast<float>(m_to_mm(in.x)));
  out.set_y(static_cast<float>(m_to_mm(in.y)));
  out.set_orientation(static_cast<float>(in.orientation));
  out.set_pixel_x(static_cast<float>(in.pixel_x));
  out.set_pixel_y(static_cast<float>(in.pixel_y));
}

void add_line(SSL_GeometryFieldSize& field, const char* name, SSL_FieldShapeType type, double x1,
              double y1, double x2, double y2, double thickness_mm) {
  SSL_FieldLineSegment* line = field.add_field_lines();
  line->set_name(name);
  line->set_type(type);
  line->mutable_p1()->set_x(static_cast<float>(x1));
  line->mutable_p1()->set_y(static_cast<float>(y1));
  line->mutable_p2()->set_x(static_cast<float>(x2));
  line->mutable_p2()->set_y(static_cast<float>(y2));
  line->set_thickness(static_cast<float>(thickness_mm));
}

// The markings SSL-Vision reports for a standard field, in mm.
void add_markings(const field_geometry_t& f, SSL_GeometryFieldSize& field) {
  const double hl = m_to_mm(f.field_length) / 2;
  const double hw = m_to_mm(f.field_width) / 2;
  const double lw = m_to_mm(f.line_width);
  const double pd = m_to_mm(f.penalty_area_depth);
  const double pw = m_to_mm(f.penalty_area_width) / 2;
  add_line(field, "TopTouchLine", TopTouchLine, -hl, hw, hl, hw, lw);
  add_line(field, "BottomTouchLine", BottomTouchLine, -hl, -hw, hl, -hw, lw);
  add_line(field, "LeftGoalLine", LeftGoalLine, -hl, -hw, -hl, hw, lw);
  add_line(field, "RightGoalLine", RightGoalLine, hl, -hw, hl, hw, lw);
  add_line(field, "HalfwayLine", HalfwayLine, 0, -hw, 0, hw, lw);
  add_line(field, "CenterLine", CenterLine, -hl, 0, hl, 0, lw);
  add_line(field, "LeftPenaltyStretch", LeftPenaltyStretch, -hl + pd, -pw, -hl + pd, pw, lw);
  add_line(field, "RightPenaltyStretch", RightPenaltyStretch, hl - pd, -pw, hl - pd, pw, lw);
  add_line(field, "LeftFieldLeftPenaltyStretch", LeftFieldLeftPenaltyStretch, -hl, -pw, -hl + pd,
           -pw, lw);
  add_line(field, "LeftFieldRightPenaltyStretch", LeftFieldRightPenaltyStretch, -hl, pw, -hl + pd,
           pw, lw);
  add_line(field, "RightFieldLeftPenaltyStretch", RightFieldLeftPenaltyStretch, hl, pw, hl - pd, pw,
           lw);
  add_line(field, "RightFieldRightPenaltyStretch", RightFieldRightPenaltyStretch, hl, -pw, hl - pd,
           -pw, lw);
  SSL_FieldCircularArc* circle = field.add_field_arcs();
  circle->set_name("CenterCircle");
  circle->set_type(CenterCircle);
  circle->mutable_center()->set_x(0);
  circle->mutable_center()->set_y(0);
  circle->set_radius(static_cast<float>(m_to_mm(f.center_circle_radius)));
  circle->set_a1(0);
  circle->set_a2(static_cast<float>(2 * kPi));
  circle->set_thickness(static_cast<float>(lw));
}

// Rotates v by the unit quaternion (w, x, y, z).
std::array<double, 3> rotate(const double q[4], const std::array<double, 3>& v) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  // v' = v + 2 w (u x v) + 2 u x (u x v), u = (x, y, z)
  const std::array<double, 3> c{y * v[2] - z * v[1], z * v[0] - x * v[2], x * v[1] - y * v[0]};
  const std::array<double, 3> cc{y * c[2] - z * c[1], z * c[0] - x * c[2], x * c[1] - y * c[0]};
  return {v[0] + 2 * (w * c[0] + cc[0]), v[1] + 2 * (w * c[1] + cc[1]),
          v[2] + 2 * (w * c[2] + cc[2])};
}

void fill_calibration(const camera_calibration_t& in, SSL_GeometryCameraCalibration& out) {
  out.set_camera_id(static_cast<uint32_t>(in.camera_id));
  out.set_focal_length(static_cast<float>(in.focal_length));
  out.set_principal_point_x(static_cast<float>(in.principal_x));
  out.set_principal_point_y(static_cast<float>(in.principal_y));
  out.set_distortion(static_cast<float>(in.distortion));
  // Ours: camera -> field rotation. SSL: world -> camera, so the conjugate,
  // and t = -R_wc * centre.
  const double world_to_camera[4] = {in.orientation[0], -in.orientation[1], -in.orientation[2],
                                     -in.orientation[3]};
  out.set_q0(static_cast<float>(world_to_camera[1]));
  out.set_q1(static_cast<float>(world_to_camera[2]));
  out.set_q2(static_cast<float>(world_to_camera[3]));
  out.set_q3(static_cast<float>(world_to_camera[0]));
  const std::array<double, 3> centre_mm{m_to_mm(in.position[0]), m_to_mm(in.position[1]),
                                        m_to_mm(in.position[2])};
  const std::array<double, 3> t = rotate(world_to_camera, centre_mm);
  out.set_tx(static_cast<float>(-t[0]));
  out.set_ty(static_cast<float>(-t[1]));
  out.set_tz(static_cast<float>(-t[2]));
  out.set_derived_camera_world_tx(static_cast<float>(centre_mm[0]));
  out.set_derived_camera_world_ty(static_cast<float>(centre_mm[1]));
  out.set_derived_camera_world_tz(static_cast<float>(centre_mm[2]));
  if (in.image_width > 0 && in.image_height > 0) {  // 0 x 0: an image without edge
    out.set_pixel_image_width(static_cast<uint32_t>(in.image_width));
    out.set_pixel_image_height(static_cast<uint32_t>(in.image_height));
  }
}

}  // namespace

BallModel load_ball_model(const std::string& config_dir, const std::string& name) {
  const auto config = ConfigFile::load(resolve_config(config_dir, "balls", name));
  BallModel model;
  model.sliding_deceleration = config.real_in("SLIDING_DECELERATION", 0, 100);
  model.rolling_deceleration = config.real_in("ROLLING_DECELERATION", 0, 100);
  model.slide_to_roll_ratio = config.real_in("SLIDE_TO_ROLL_RATIO", 0, 1);
  return model;  // the physics keys of the ball config are not ours to check
}

bool forwardable(const vision_frame_t& frame) {
  const auto fits = [](double v) { return fits_ssl(v); };
  bool ok = fits(frame.t_capture) && fits(frame.t_sent);
  for (const vision_ball_t& b : frame.balls) {
    ok = ok && fits(b.confidence) && fits(b.x) && fits(b.y) && fits(b.pixel_x) && fits(b.pixel_y) &&
         fits(b.area) && b.area >= 0;
  }
  for (const auto* robots : {&frame.robots_yellow, &frame.robots_blue}) {
    for (const vision_robot_t& r : *robots) {
      ok = ok && fits(r.confidence) && fits(r.x) && fits(r.y) && fits(r.orientation) &&
           fits(r.pixel_x) && fits(r.pixel_y);
    }
  }
  return ok;
}

bool forwardable(const vision_geometry_t& geometry) {
  // 1e6 m = 1e9 mm: whole millimetres stay within int32 (m_to_whole_mm).
  const auto size = [](double metres) {
    return std::isfinite(metres) && metres >= 0 && metres <= 1e6;
  };
  const field_geometry_t& f = geometry.field;
  bool ok = size(f.field_length) && size(f.field_width) && size(f.boundary_width) &&
            size(f.line_width) && size(f.goal_width) && size(f.goal_depth) && size(f.goal_height) &&
            size(f.center_circle_radius) && size(f.penalty_area_depth) &&
            size(f.penalty_area_width) && size(f.ball_radius) && size(f.penalty_mark_distance) &&
            size(f.boundary_width_goal_line) && size(f.goal_substitution_area_width);
  for (const camera_calibration_t& c : geometry.cameras) {
    ok = ok && fits_ssl(c.focal_length) && fits_ssl(c.principal_x) && fits_ssl(c.principal_y) &&
         fits_ssl(c.distortion) && c.image_width >= 0 && c.image_height >= 0;
    for (double v : c.position) ok = ok && fits_ssl(v);
    for (double v : c.orientation) ok = ok && fits_ssl(v);
  }
  return ok;
}

SSL_WrapperPacket detection_packet(const vision_frame_t& frame) {
  SSL_WrapperPacket packet;
  packet.set_source(kPacketSource);
  SSL_DetectionFrame* out = packet.mutable_detection();
  // SSL frame numbers are uint32; ours are int64 and wrap the same way.
  out->set_frame_number(static_cast<uint32_t>(frame.frame_number));
  out->set_t_capture(frame.t_capture);
  out->set_t_sent(frame.t_sent);
  out->set_camera_id(static_cast<uint32_t>(frame.camera_id));
  for (const vision_ball_t& ball : frame.balls) {
    SSL_DetectionBall* b = out->add_balls();
    b->set_confidence(ball.confidence);
    b->set_x(static_cast<float>(m_to_mm(ball.x)));
    b->set_y(static_cast<float>(m_to_mm(ball.y)));
    b->set_pixel_x(static_cast<float>(ball.pixel_x));
    b->set_pixel_y(static_cast<float>(ball.pixel_y));
    // SSL's area is a whole number of pixels; 0 = not measured, left out.
    if (ball.area >= 0.5) b->set_area(static_cast<uint32_t>(std::lround(ball.area)));
  }
  for (const vision_robot_t& robot : frame.robots_yellow)
    fill_robot(robot, *out->add_robots_yellow());
  for (const vision_robot_t& robot : frame.robots_blue) fill_robot(robot, *out->add_robots_blue());
  return packet;
}

SSL_WrapperPacket geometry_packet(const vision_geometry_t& geometry, const GeometryExtras& extras) {
  SSL_WrapperPacket packet;
  packet.set_source(kPacketSource);
  SSL_GeometryData* data = packet.mutable_geometry();
  const field_geometry_t& f = geometry.field;
  SSL_GeometryFieldSize* field = data->mutable_field();
  field->set_field_length(m_to_whole_mm(f.field_length));
  field->set_field_width(m_to_whole_mm(f.field_width));
  field->set_goal_width(m_to_whole_mm(f.goal_width));
  field->set_goal_depth(m_to_whole_mm(f.goal_depth));
  field->set_boundary_width(m_to_whole_mm(f.boundary_width));
  field->set_boundary_width_goal_line(m_to_whole_mm(f.boundary_width_goal_line));
  field->set_goal_substitution_area_width(m_to_whole_mm(f.goal_substitution_area_width));
  add_markings(f, *field);
  field->set_penalty_area_depth(m_to_whole_mm(f.penalty_area_depth));
  field->set_penalty_area_width(m_to_whole_mm(f.penalty_area_width));
  field->set_center_circle_radius(m_to_whole_mm(f.center_circle_radius));
  field->set_line_thickness(m_to_whole_mm(f.line_width));
  field->set_goal_center_to_penalty_mark(m_to_whole_mm(f.penalty_mark_distance));
  field->set_goal_height(m_to_whole_mm(f.goal_height));
  field->set_ball_radius(static_cast<float>(m_to_mm(f.ball_radius)));
  if (extras.max_robot_radius > 0) {
    field->set_max_robot_radius(static_cast<float>(m_to_mm(extras.max_robot_radius)));
  }
  for (const camera_calibration_t& camera : geometry.cameras) {
    fill_calibration(camera, *data->add_calib());
  }
  if (extras.ball_model) {
    // SSL reports the model in m/s^2 with decelerations as negative numbers.
    SSL_BallModelStraightTwoPhase* model = data->mutable_models()->mutable_straight_two_phase();
    model->set_acc_slide(-extras.ball_model->sliding_deceleration);
    model->set_acc_roll(-extras.ball_model->rolling_deceleration);
    model->set_k_switch(extras.ball_model->slide_to_roll_ratio);
  }
  return packet;
}

}  // namespace ubersim::ssl
