#include "ubersim/radio/command_link.hpp"

#include <algorithm>
#include <limits>

namespace ubersim::radio {
namespace {
constexpr double kLongAgo = -std::numeric_limits<double>::infinity();
}

CommandLink::CommandLink(const RadioProfile& profile, Team team, std::uint64_t seed)
    : profile_(profile),
      team_(team),
      random_(seed, team, Direction::Command),
      busy_until_(kLongAgo),
      last_t_apply_(kLongAgo),
      next_delay_(random_.delay(profile_.command)) {}

void CommandLink::set_profile(const RadioProfile& profile) {
  profile_ = profile;
  next_delay_ = random_.delay(profile_.command);
}

double CommandLink::earliest_apply(double earliest_arrival) const {
  double t_transmit = std::max(busy_until_, earliest_arrival);
  if (waiting_) t_transmit = std::min(t_transmit, std::max(busy_until_, waiting_->t_received));
  if (t_transmit == std::numeric_limits<double>::infinity()) return t_transmit;
  return std::max(t_transmit + next_delay_, last_t_apply_);
}

std::optional<sim_commands_t> CommandLink::offer(radio_packet_t packet, double now) {
  ++stats_.offered;
  if (waiting_) ++stats_.superseded;
  waiting_ = Waiting{std::move(packet), now};
  return poll(now);
}

std::optional<sim_commands_t> CommandLink::poll(double now) {
  if (!waiting_ || !free_at(now)) return std::nullopt;
  Waiting waiting = std::move(*waiting_);
  waiting_.reset();
  // The link freed at busy_until_, possibly between two SIM_STATEs.
  const double t_transmit = std::max(busy_until_, waiting.t_received);
  return transmit(std::move(waiting), t_transmit);
}

void CommandLink::reset() {
  waiting_.reset();
  busy_until_ = kLongAgo;
  last_t_apply_ = kLongAgo;
}

std::optional<sim_commands_t> CommandLink::transmit(Waiting waiting, double t_transmit) {
  ++stats_.transmitted;
  busy_until_ =
      profile_.max_packet_rate > 0 ? t_transmit + 1.0 / profile_.max_packet_rate : t_transmit;
  if (random_.happens(profile_.command.packet_loss)) {
    ++stats_.lost_packets;
    return std::nullopt;
  }
  sim_commands_t out;
  out.team = static_cast<std::int8_t>(team_);
  out.sequence = waiting.packet.sequence;
  out.t_received = waiting.t_received;
  out.command_timeout = profile_.command_timeout;
  for (auto& command : waiting.packet.commands) {
    if (random_.happens(profile_.command.robot_loss)) {
      ++stats_.lost_entries;
      continue;  // that robot stays on its previous command
    }
    out.commands.push_back(std::move(command));
  }
  out.num_commands = static_cast<std::int32_t>(out.commands.size());
  // A radio delivers in order: jitter may delay a packet, never let a later one overtake it.
  out.t_apply = std::max(t_transmit + next_delay_, last_t_apply_);
  next_delay_ = random_.delay(profile_.command);
  last_t_apply_ = out.t_apply;
  if (out.commands.empty()) return std::nullopt;  // nothing reached any robot
  ++stats_.forwarded_packets;
  stats_.forwarded_entries += out.commands.size();
  return out;
}

}  // namespace ubersim::radio
