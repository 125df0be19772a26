#include "ubersim/ssl_bridge/lcm_team_door.hpp"

#include <algorithm>
#include <cmath>
#include <regex>
#include <ubersim/team_t.hpp>

#include "ubersim/delay_line.hpp"
#include "ubersim/spdlog.hpp"
#include "ubersim/ssl_bridge/timed_inputs.hpp"
#include "ubersim/topics.hpp"

namespace ubersim::ssl {
namespace {

template <class Msg>
std::string encoded(const Msg& message) {
  std::string bytes(static_cast<std::size_t>(message.getEncodedSize()), '\0');
  message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

}  // namespace

std::optional<std::string> private_lcm_url(const std::string& main_url) {
  static const std::regex udpm(R"(udpm://([0-9.]+):([0-9]+)(\?.*)?)");
  std::smatch match;
  if (!std::regex_match(main_url, match, udpm)) return std::nullopt;
  const int port = std::stoi(match[2]);
  if (port < 1 || port >= 65535) return std::nullopt;
  return "udpm://" + match[1].str() + ":" + std::to_string(port + 1) + "?ttl=0";
}

std::string with_lcm_url(const std::string& command, const std::string& url) {
  // The URL is ours (digits, dots, ?, =, :, /), so single quotes suffice.
  return "LCM_DEFAULT_URL='" + url + "'; export LCM_DEFAULT_URL; " + command;
}

std::string apply_team_protocols(const std::vector<std::pair<std::string, std::string>>& protocols,
                                 const std::string& main_url, TeamGroupOptions& teams,
                                 LcmDoorOptions& door) {
  std::vector<std::string> given;
  for (const auto& entry : protocols) {
    const std::string& colour = entry.first;  // captured below: not a structured binding
    const std::string& protocol = entry.second;
    if (protocol != "ssl" && protocol != "lcm" && protocol != "grsim") {
      return "--team-protocol: protocol '" + protocol + "' is not ssl, lcm or grsim";
    }
    const auto command = std::find_if(teams.commands.begin(), teams.commands.end(),
                                      [&](const TeamCommand& c) { return c.colour() == colour; });
    if (command == teams.commands.end()) {
      return "--team-protocol: no --team-command for '" + colour + "'";
    }
    if (std::count(given.begin(), given.end(), colour) > 0) {
      return "--team-protocol: " + colour + " given twice";
    }
    given.push_back(colour);
    if (protocol == "ssl") continue;
    if (protocol == "grsim") {
      command->protocol = TeamProtocol::Grsim;
      continue;
    }
    if (command->both) return "--team-protocol: an LCM program plays one colour, not both";
    if (door.url.empty()) {
      const std::optional<std::string> url = private_lcm_url(main_url);
      if (!url) {
        return "--team-protocol lcm: the LCM URL '" + main_url +
               "' is not udpm://ADDRESS:PORT; give the team's own bus with --team-lcm-url";
      }
      door.url = *url;
    }
    if (door.url == main_url) return "--team-lcm-url: the team's bus must not be the main bus";
    command->protocol = TeamProtocol::Lcm;
    door.teams.push_back(command->team);
    command->command = with_lcm_url(command->command, door.url);
  }
  return "";
}

std::vector<Team> grsim_teams(const TeamGroupOptions& teams) {
  std::vector<Team> grsim;
  for (const TeamCommand& command : teams.commands) {
    if (command.protocol != TeamProtocol::Grsim) continue;
    grsim.push_back(command.team);
    if (command.both) grsim.push_back(Team::Blue);
  }
  return grsim;
}

LcmTeamDoor::LcmTeamDoor(MessageBus& main, const ChannelNames& channels, LcmDoorOptions options,
                         PublishRadio publish_radio)
    : main_(main),
      channels_(channels),
      options_(std::move(options)),
      publish_radio_(std::move(publish_radio)),
      private_(options_.url) {
  subscribe(main_, channels_, topics::kVisionGeometry, [this](const vision_geometry_t& g) {
    if (holding_) geometry_ = encoded(g);
  });
  subscribe(main_, channels_, topics::kReferee, [this](const referee_t& r) {
    if (holding_) referee_.push_back(r);
  });
  for (Team team : options_.teams) {
    subscribe(main_, channels_, topics::kRadioFeedback.of(team), [this](const radio_feedback_t& f) {
      if (holding_) feedback_.push_back(f);
    });
    subscribe(private_, channels_, topics::kRadio.of(team), [this, team](const radio_packet_t& p) {
      radio_packet_t packet = p;
      packet.team = team == Team::Yellow ? int8_t{team_t::YELLOW} : int8_t{team_t::BLUE};
      packet.t_sent = static_cast<double>(draining_at_ns_) / 1e9;
      publish_radio_(team, packet);
      ++counters_[std::string(team_name(team)) + " radio packets relayed"];
    });
    spdlog::info("team {}: speaks LCM on its own bus {} (the bridge relays it, timed)",
                 team_name(team), options_.url);
  }
}

void LcmTeamDoor::hold(const vision_frame_t& frame) {
  if (holding_) vision_.push_back(frame);
}

// The geometry goes out when it changed, and again every second of sim time
// (what the vision emulator does in wall time), always with a frame.
void LcmTeamDoor::deliver_geometry(double t) {
  constexpr double kRepeat = 1.0;  // s of sim time
  if (geometry_.empty()) return;
  if (geometry_ == geometry_sent_ && t < geometry_next_) return;
  private_.publish_encoded(channel_name(channels_, topics::kVisionGeometry), geometry_.data(),
                           geometry_.size());
  ++counters_["geometry relayed"];
  geometry_sent_ = geometry_;
  geometry_next_ = t + kRepeat;
}

void LcmTeamDoor::deliver(double t, double settled) {
  if (!holding_) return;
  deliver_geometry(t);
  for (const referee_t& referee :
       take_until(referee_, settled, [](const referee_t& r) { return r.sim_time; })) {
    publish(private_, channels_, topics::kReferee, referee);
    ++counters_["referee relayed"];
  }
  for (const radio_feedback_t& feedback :
       take_until(feedback_, settled + kReleaseEpsilon,
                  [](const radio_feedback_t& f) { return f.t_sent; })) {
    const Team team = feedback.team == team_t::YELLOW ? Team::Yellow : Team::Blue;
    publish(private_, channels_, topics::kRadioFeedback.of(team), feedback);
    ++counters_["feedback relayed"];
  }
  for (const vision_frame_t& frame : vision_) {
    publish(private_, channels_, topics::kVision, frame);
    ++counters_["vision relayed"];
  }
  vision_.clear();
}

int LcmTeamDoor::drain(std::int64_t now_ns) {
  draining_at_ns_ = now_ns;
  int drained = 0;
  while (const int handled = private_.handle_pending()) drained += handled;
  return drained;
}

void LcmTeamDoor::stop_holding() {
  holding_ = false;
  vision_.clear();
  referee_.clear();
  feedback_.clear();
}

std::string LcmTeamDoor::summary() const {
  std::string text = " lcm door:";
  for (const auto& [what, count] : counters_) text += " " + what + "=" + std::to_string(count);
  return text;
}

}  // namespace ubersim::ssl
