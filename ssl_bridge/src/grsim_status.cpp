#include "ubersim/ssl_bridge/grsim_status.hpp"

#include <cmath>

namespace ubersim::ssl {

void GrsimStatus::on_feedback(Team team, const radio_feedback_t& feedback, const KickAsked& asked) {
  const auto t = static_cast<std::size_t>(team);
  if (!std::isfinite(feedback.t_measured)) return;
  for (const robot_feedback_t& in : feedback.robots) {
    // grSim has no status for robots beyond its slots; so the map stays small.
    if (in.robot_id < 0 || in.robot_id >= static_cast<int32_t>(kGrsimMaxRobots)) continue;
    Robot& robot = robots_[t][in.robot_id];
    robot.infrared = in.ball_contact;
    if (robot.charged && !in.kicker_charged) {
      const GrsimKick kick = asked(in.robot_id);
      if (kick != GrsimKick::None) {
        robot.kick = kick;
        robot.kick_until = feedback.t_measured + kGrsimKickStatusTime;
      }
    }
    if (robot.kick != GrsimKick::None && feedback.t_measured >= robot.kick_until) {
      robot.kick = GrsimKick::None;
    }
    robot.charged = in.kicker_charged;
    if (robot.infrared != robot.sent_infrared || robot.kick != robot.sent_kick) pending_[t] = true;
  }
}

std::optional<Robots_Status> GrsimStatus::changes(Team team) {
  const auto t = static_cast<std::size_t>(team);
  if (!pending_[t]) return std::nullopt;
  pending_[t] = false;
  Robots_Status out;
  for (auto& [id, robot] : robots_[t]) {
    if (robot.infrared == robot.sent_infrared && robot.kick == robot.sent_kick) continue;
    Robot_Status* status = out.add_robots_status();
    status->set_robot_id(id);
    status->set_infrared(robot.infrared);
    status->set_flat_kick(robot.kick == GrsimKick::Flat);
    status->set_chip_kick(robot.kick == GrsimKick::Chip);
    robot.sent_infrared = robot.infrared;
    robot.sent_kick = robot.kick;
  }
  if (out.robots_status_size() == 0) return std::nullopt;
  return out;
}

}  // namespace ubersim::ssl
