#include "ubersim/ssl_bridge/grsim_command_book.hpp"

#include <algorithm>
#include <ubersim/team_t.hpp>

namespace ubersim::ssl {

void GrsimCommandBook::heard(Team team, Clock::time_point now) {
  books_[index(team)].last_heard = now;
}

void GrsimCommandBook::put(Team team, const GrsimRobotCommand& command, Clock::time_point now) {
  TeamBook& book = books_[index(team)];
  const auto [found, added] = book.robots.try_emplace(command.command.robot_id);
  Entry& entry = found->second;
  if (!added && !entry.sent) ++book.superseded;
  entry.command = command;
  entry.arrived = now;
  entry.sent = false;
  book.news = true;
}

const robot_command_t* GrsimCommandBook::last(Team team, int32_t robot_id) const {
  const TeamBook& book = books_[index(team)];
  const auto found = book.robots.find(robot_id);
  return found == book.robots.end() ? nullptr : &found->second.command.command;
}

GrsimKick GrsimCommandBook::kick(Team team, int32_t robot_id) const {
  const TeamBook& book = books_[index(team)];
  const auto found = book.robots.find(robot_id);
  return found == book.robots.end() ? GrsimKick::None : found->second.command.kick;
}

radio_packet_t GrsimCommandBook::all_robots(Team team,
                                            std::optional<Clock::time_point> kicks_since) const {
  radio_packet_t out{};
  out.team = team == Team::Yellow ? int8_t{team_t::YELLOW} : int8_t{team_t::BLUE};
  for (const auto& [id, entry] : books_[index(team)].robots) {
    robot_command_t command = entry.command.command;
    if (!kicks_since || entry.arrived < *kicks_since) {
      command.kick_speed = 0;
      command.chip_speed = 0;
      command.chip_angle = 0;
    }
    out.commands.push_back(std::move(command));
  }
  out.num_commands = static_cast<int32_t>(out.commands.size());
  return out;
}

radio_packet_t GrsimCommandBook::packet(Team team, Clock::time_point now) {
  TeamBook& book = books_[index(team)];
  for (auto& [id, entry] : book.robots) entry.sent = true;
  book.news = false;
  book.last_packet = now;
  return all_robots(team, now - kGrsimKickWindow);
}

std::optional<radio_packet_t> GrsimCommandBook::due(Team team, Clock::time_point now,
                                                    Clock::duration repeat) {
  TeamBook& book = books_[index(team)];
  if (book.robots.empty() || book.news) return std::nullopt;
  if (hold_ > Clock::duration::zero() && now >= book.last_heard + hold_) {
    radio_packet_t stop = all_robots(team, std::nullopt);
    for (robot_command_t& command : stop.commands) {
      robot_command_t still{};
      still.robot_id = command.robot_id;
      still.mode = robot_command_t::MODE_LOCAL_VELOCITY;
      still.dribbler_speed = command.dribbler_speed;
      command = std::move(still);
    }
    book.robots.clear();
    ++book.stops;
    return stop;
  }
  if (now < book.last_packet + repeat) return std::nullopt;
  book.last_packet = now;
  return all_robots(team, std::nullopt);
}

std::optional<GrsimCommandBook::Clock::time_point> GrsimCommandBook::next_due(
    Team team, Clock::duration repeat) const {
  const TeamBook& book = books_[index(team)];
  if (book.robots.empty() || book.news) return std::nullopt;
  const Clock::time_point repeat_at = book.last_packet + repeat;
  if (hold_ <= Clock::duration::zero()) return repeat_at;
  return std::min(repeat_at, book.last_heard + hold_);
}

}  // namespace ubersim::ssl
