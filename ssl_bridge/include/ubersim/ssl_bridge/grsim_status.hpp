#pragma once
// grSim's robot status (Robots_Status) from ubersim's radio feedback. grSim
// keeps, per robot, whether the ball touches its kicker ("infrared") and
// whether it kicks (for 10 frames after a kick, flat or chip), and sends a
// team the robots whose status changed since it last sent (SSLWorld::
// recvActions). Here the ball contact is the feedback's `ball_contact`, and a
// kick is the kicker going from charged to discharged while the robot's grSim
// command asks for one (flat or chip as grSim would name it).
#include <grSim_Robotstatus.pb.h>

#include <array>
#include <functional>
#include <map>
#include <optional>
#include <ubersim/radio_feedback_t.hpp>

#include "ubersim/channels.hpp"
#include "ubersim/ssl_bridge/grsim_translation.hpp"

namespace ubersim::ssl {

// grSim shows a kick for 10 of its frames (Kicker::kick, kickstate = 10) at 60 frames/s.
inline constexpr double kGrsimKickStatusTime = 10.0 / 60.0;  // s of sim time

class GrsimStatus {
 public:
  using KickAsked = std::function<GrsimKick(int32_t robot_id)>;
  void on_feedback(Team team, const radio_feedback_t& feedback, const KickAsked& asked);
  // Some robot's status changed since changes() was last asked.
  bool pending() const { return pending_[0] || pending_[1]; }
  // The team's robots whose status changed since the last call (nullopt: none).
  std::optional<Robots_Status> changes(Team team);

 private:
  struct Robot {
    bool infrared = false;
    GrsimKick kick = GrsimKick::None;
    double kick_until = 0;  // sim time the kick status ends
    bool charged = false;
    bool sent_infrared = false;  // what the team was last told (grSim starts at none)
    GrsimKick sent_kick = GrsimKick::None;
  };
  std::array<std::map<int32_t, Robot>, 2> robots_{};
  std::array<bool, 2> pending_{};
};

}  // namespace ubersim::ssl
