#pragma once
// The newest grSim command of every robot, per team, between the grSim port
// and RADIO_<TEAM>. A team may send 50,000 single-robot packets a second; the
// book keeps one command per robot (so its size is bounded by the robot ids,
// whatever arrives), counts the commands a newer one replaced before they went
// out, and gives the radio one packet with every robot's newest command (a
// newer radio packet replaces a waiting one on a rate-limited link, so each
// packet must carry every robot).
//
// Kicks: grSim kicks once, when the packet arrives (if the ball touches). A
// robot's kick rides in the packets published within kGrsimKickWindow of its
// command's arrival, so the radio's newest-wins link transmits it at least
// once (links of 20 Hz and faster), and not in later ones.
//
// Silence: grSim stops a team's robots when it has heard nothing from that
// team for 1 s (src/mainwindow.cpp, MainWindow::update); `hold` is that time.
// Until then the robots keep their last command (the book repeats it, without
// its kick, so the radio's own command timeout does not stop them earlier);
// then they get one stop (velocities 0, dribbler as it was: grSim resets only
// the wheel speeds) and the book forgets them.
#include <array>
#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <ubersim/radio_packet_t.hpp>

#include "ubersim/channels.hpp"
#include "ubersim/ssl_bridge/grsim_translation.hpp"

namespace ubersim::ssl {

inline constexpr std::chrono::milliseconds kGrsimKickWindow{50};

class GrsimCommandBook {
 public:
  using Clock = std::chrono::steady_clock;

  // hold <= 0: never stop a silent team (grSim releases up to v2.5.0).
  explicit GrsimCommandBook(Clock::duration hold) : hold_(hold) {}

  // The team spoke (any grSim command datagram): its robots are held from now.
  void heard(Team team, Clock::time_point now);
  // A robot's newest command, arrived at `now`; one not yet sent that it
  // replaces is superseded.
  void put(Team team, const GrsimRobotCommand& command, Clock::time_point now);
  // The robot's last command (null: none), for wheels grSim is not given.
  const robot_command_t* last(Team team, int32_t robot_id) const;
  // The kick the robot's newest command asks for.
  GrsimKick kick(Team team, int32_t robot_id) const;

  // Something new to send for the team.
  bool has_news(Team team) const { return books_[index(team)].news; }
  // Every robot's newest command, kicks asked within kGrsimKickWindow
  // included; marks them sent.
  radio_packet_t packet(Team team, Clock::time_point now);
  // What is due for a silent team at `now`: the repeat (every `repeat`, no
  // kicks) while it is held, then the stop once. nullopt: nothing.
  std::optional<radio_packet_t> due(Team team, Clock::time_point now, Clock::duration repeat);
  // When due() has something next (nullopt: nothing until the team speaks).
  std::optional<Clock::time_point> next_due(Team team, Clock::duration repeat) const;

  std::uint64_t superseded(Team team) const { return books_[index(team)].superseded; }
  std::uint64_t stops(Team team) const { return books_[index(team)].stops; }

 private:
  struct Entry {
    GrsimRobotCommand command;
    Clock::time_point arrived{};
    bool sent = false;
  };
  struct TeamBook {
    std::map<int32_t, Entry> robots;
    bool news = false;
    Clock::time_point last_heard{};
    Clock::time_point last_packet{};
    std::uint64_t superseded = 0;
    std::uint64_t stops = 0;
  };
  static std::size_t index(Team team) { return static_cast<std::size_t>(team); }
  // kicks_since: the kicks of commands that arrived from then on ride along.
  radio_packet_t all_robots(Team team, std::optional<Clock::time_point> kicks_since) const;

  Clock::duration hold_;
  std::array<TeamBook, 2> books_{};
};

}  // namespace ubersim::ssl
