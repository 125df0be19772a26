#pragma once
// The demo team's core: what it sees (WorldModel, RefereeFollower) and the
// radio packet it sends for a vision frame. Its shell (DemoTeamShell,
// demo_team_shell.cpp) puts it on the process host.
#include <cstdint>
#include <string>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/referee_t.hpp>
#include <ubersim/vision_frame_t.hpp>
#include <ubersim/vision_geometry_t.hpp>
#include <vector>

#include "behaviour.hpp"
#include "referee_rules.hpp"
#include "ubersim/channels.hpp"
#include "ubersim/common_options.hpp"
#include "ubersim/message_bus.hpp"

namespace demo {

struct DemoTeamOptions {
  ubersim::CommonOptions common;
  std::string team_text = "yellow";
  std::string mode = "play";
  std::string defends_text;
  double rate = 60.0;
  double figure8_speed = 0.8;
  double figure8_size = 1.0;
  bool sync = false;
  TeamSetup team;
};

// The team itself: each vision frame updates what it sees, and at --rate (in
// capture time) it sends one radio packet. In sync mode it answers every
// frame: with an empty packet whose t_sent is the frame's t_capture when it
// has nothing to send (docs/sync.md).
class DemoTeam {
 public:
  DemoTeam(const DemoTeamOptions& options, ubersim::Team own, ubersim::MessageBus& bus,
           const ubersim::ChannelNames& channels);

  const TeamSetup& setup() const { return team_; }
  std::int64_t packets() const { return sequence_; }

  void on_geometry(const ubersim::vision_geometry_t& geometry);
  void on_referee(const ubersim::referee_t& referee) { referee_.update(referee); }
  void on_frame(const ubersim::vision_frame_t& frame);

 private:
  std::vector<ubersim::robot_command_t> commands() const;
  void send(std::vector<ubersim::robot_command_t> commands, double t_sent);

  const DemoTeamOptions& options_;
  TeamSetup team_;
  bool yellow_;
  std::int8_t team_code_;
  ubersim::MessageBus& bus_;
  std::string radio_channel_;  // RADIO_<TEAM>
  WorldModel world_;
  RefereeFollower referee_;
  double last_sent_ = -1e9;
  std::int64_t sequence_ = 0;
};

}  // namespace demo
