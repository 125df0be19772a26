#include "ubersim/dds_bridge/sample_checks.hpp"

#include <cmath>
#include <ubersim/team_t.hpp>

#include "ubersim/radio/command_validator.hpp"

namespace ubersim::dds {
namespace {

// Remembers the first non-finite value it is shown.
class FiniteCheck {
 public:
  void operator()(const std::string& name, double value) {
    if (first_.empty() && !std::isfinite(value)) first_ = name;
  }
  template <std::size_t N>
  void operator()(const std::string& name, const double (&values)[N]) {
    for (std::size_t i = 0; i < N; ++i) (*this)(name + "[" + std::to_string(i) + "]", values[i]);
  }
  void operator()(const std::string& name, const std::vector<double>& values) {
    for (std::size_t i = 0; i < values.size(); ++i)
      (*this)(name + "[" + std::to_string(i) + "]", values[i]);
  }
  const std::string& first() const { return first_; }

 private:
  std::string first_;
};

std::string at(const std::string& array, std::size_t i) {
  return array + "[" + std::to_string(i) + "].";
}

void check_body(FiniteCheck& check, const std::string& name, const body_state_t& body) {
  check(name + ".position", body.position);
  check(name + ".orientation", body.orientation);
  check(name + ".linear_velocity", body.linear_velocity);
  check(name + ".angular_velocity", body.angular_velocity);
}

void check_field(FiniteCheck& check, const std::string& prefix, const field_geometry_t& f) {
  for (const auto& [name, value] :
       {std::pair<const char*, double>{"field_length", f.field_length},
        {"field_width", f.field_width},
        {"boundary_width", f.boundary_width},
        {"line_width", f.line_width},
        {"goal_width", f.goal_width},
        {"goal_depth", f.goal_depth},
        {"goal_height", f.goal_height},
        {"goal_wall_thickness", f.goal_wall_thickness},
        {"wall_height", f.wall_height},
        {"wall_thickness", f.wall_thickness},
        {"center_circle_radius", f.center_circle_radius},
        {"penalty_area_depth", f.penalty_area_depth},
        {"penalty_area_width", f.penalty_area_width},
        {"ball_radius", f.ball_radius},
        {"penalty_mark_distance", f.penalty_mark_distance},
        {"boundary_width_goal_line", f.boundary_width_goal_line},
        {"goal_substitution_area_width", f.goal_substitution_area_width}})
    check(prefix + name, value);
}

// Moves validator findings into an admission.
void record(Admission& admission, const std::vector<radio::Finding>& findings) {
  for (const auto& finding : findings) {
    std::string detail = radio::problem_name(finding.problem);
    if (finding.robot_id >= 0) detail += " (robot " + std::to_string(finding.robot_id) + ")";
    if (!finding.detail.empty()) detail += ": " + finding.detail;
    admission.findings.push_back({radio::problem_name(finding.problem), detail});
  }
}

// Runs the radio emulator's validator over a packet's commands. The bridge
// does not know which robots are on the field: every id in the packet counts
// as present with an unknown wheel count (0), so only the field-independent
// checks apply here.
Admission validate(radio_packet_t& packet, Team channel_team, const radio::CommandLimits& limits) {
  radio::RobotsOnField robots;
  for (const auto& command : packet.commands) robots[command.robot_id] = 0;
  radio::Validated validated = radio::validate_packet(packet, channel_team, limits, robots);
  Admission admission;
  record(admission, validated.findings);
  if (!validated.packet_ok) {
    admission.forward = false;
    return admission;
  }
  // A packet that had entries and lost them all carries nothing: dropped, as
  // the radio emulator drops it. A packet sent empty goes on as it came.
  if (validated.packet.commands.empty() && !packet.commands.empty()) {
    admission.forward = false;
    return admission;
  }
  admission.entries_removed = packet.commands.size() - validated.packet.commands.size();
  packet = std::move(validated.packet);
  return admission;
}

}  // namespace

std::string non_finite_field(const vision_frame_t& frame) {
  FiniteCheck check;
  check("t_capture", frame.t_capture);
  check("t_sent", frame.t_sent);
  for (std::size_t i = 0; i < frame.balls.size(); ++i) {
    const auto& b = frame.balls[i];
    const std::string p = at("balls", i);
    check(p + "confidence", b.confidence);
    check(p + "x", b.x);
    check(p + "y", b.y);
    check(p + "pixel_x", b.pixel_x);
    check(p + "pixel_y", b.pixel_y);
    check(p + "area", b.area);
  }
  for (const auto* team : {&frame.robots_yellow, &frame.robots_blue}) {
    const std::string array = team == &frame.robots_yellow ? "robots_yellow" : "robots_blue";
    for (std::size_t i = 0; i < team->size(); ++i) {
      const auto& r = (*team)[i];
      const std::string p = at(array, i);
      check(p + "confidence", r.confidence);
      check(p + "x", r.x);
      check(p + "y", r.y);
      check(p + "orientation", r.orientation);
      check(p + "pixel_x", r.pixel_x);
      check(p + "pixel_y", r.pixel_y);
    }
  }
  return check.first();
}

std::string non_finite_field(const field_geometry_t& field) {
  FiniteCheck check;
  check_field(check, "", field);
  return check.first();
}

std::string non_finite_field(const vision_geometry_t& geometry) {
  FiniteCheck check;
  check("t_sent", geometry.t_sent);
  check_field(check, "field.", geometry.field);
  for (std::size_t i = 0; i < geometry.cameras.size(); ++i) {
    const auto& c = geometry.cameras[i];
    const std::string p = at("cameras", i);
    check(p + "focal_length", c.focal_length);
    check(p + "principal_x", c.principal_x);
    check(p + "principal_y", c.principal_y);
    check(p + "position", c.position);
    check(p + "orientation", c.orientation);
    check(p + "distortion", c.distortion);
  }
  return check.first();
}

std::string non_finite_field(const radio_feedback_t& feedback) {
  FiniteCheck check;
  check("t_measured", feedback.t_measured);
  check("t_sent", feedback.t_sent);
  return check.first();
}

std::string non_finite_field(const sim_state_t& state) {
  FiniteCheck check;
  check("sim_time", state.sim_time);
  check("dt", state.dt);
  check("speed_factor", state.speed_factor);
  check_body(check, "ball", state.ball);
  for (std::size_t i = 0; i < state.robots.size(); ++i) {
    const auto& r = state.robots[i];
    const std::string p = at("robots", i);
    check(p + "x", r.x);
    check(p + "y", r.y);
    check(p + "orientation", r.orientation);
    check(p + "vx", r.vx);
    check(p + "vy", r.vy);
    check(p + "omega", r.omega);
    check_body(check, p + "body", r.body);
    check(p + "wheel_speeds", r.wheel_speeds);
    check(p + "last_command_time", r.last_command_time);
  }
  return check.first();
}

std::string non_finite_field(const sim_control_t& control) {
  FiniteCheck check;
  for (std::size_t i = 0; i < control.robots.size(); ++i) {
    const auto& r = control.robots[i];
    const std::string p = at("robots", i);
    check(p + "x", r.x);
    check(p + "y", r.y);
    check(p + "orientation", r.orientation);
    check(p + "vx", r.vx);
    check(p + "vy", r.vy);
    check(p + "omega", r.omega);
  }
  check("ball.position", control.ball.position);
  check("ball.linear_velocity", control.ball.linear_velocity);
  check("speed_factor", control.speed_factor);
  return check.first();
}

std::string non_finite_field(const sim_control_ack_t& ack) {
  FiniteCheck check;
  check("sim_time", ack.sim_time);
  return check.first();
}

Admission admit_radio(radio_packet_t& packet, Team channel_team,
                      const radio::CommandLimits& limits) {
  return validate(packet, channel_team, limits);
}

Admission admit_commands(sim_commands_t& commands, const radio::CommandLimits& limits) {
  FiniteCheck check;
  check("t_received", commands.t_received);
  check("t_apply", commands.t_apply);
  check("command_timeout", commands.command_timeout);
  if (!check.first().empty()) {
    Admission admission;
    admission.forward = false;
    admission.findings.push_back({"NaN/Inf", check.first() + " is not finite"});
    return admission;
  }
  // The same checks as a radio packet of that team: wrap, validate, unwrap.
  radio_packet_t packet{};
  packet.team = commands.team;
  packet.sequence = commands.sequence;
  packet.commands = std::move(commands.commands);
  packet.num_commands = static_cast<std::int32_t>(packet.commands.size());
  const Team team = commands.team == team_t::BLUE ? Team::Blue : Team::Yellow;
  Admission admission = validate(packet, team, limits);
  commands.commands = std::move(packet.commands);
  commands.num_commands = static_cast<std::int32_t>(commands.commands.size());
  return admission;
}

}  // namespace ubersim::dds
