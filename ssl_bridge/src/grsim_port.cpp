#include "ubersim/ssl_bridge/grsim_port.hpp"

#include <arpa/inet.h>
#include <sys/socket.h>

#include <algorithm>
#include <cerrno>
#include <stdexcept>
#include <ubersim/team_t.hpp>

#include "ubersim/delay_line.hpp"
#include "ubersim/spdlog.hpp"
#include "ubersim/ssl_bridge/datagram_decoding.hpp"
#include "ubersim/ssl_bridge/timed_inputs.hpp"
#include "ubersim/topics.hpp"

namespace ubersim::ssl {
namespace {

constexpr const char* kGrsimSender = "ubersim_ssl_bridge_grsim";
// Asked of the kernel for the port's receive buffer, so a burst waits there
// rather than being lost (the kernel caps it at net.core.rmem_max).
constexpr int kReceiveBufferBytes = 4 << 20;

UdpSocket open_port(const GrsimOptions& options) {
  UdpSocket socket = UdpSocket::bound(options.listen_address, options.port);
  const int one = 1;
  // The kernel then counts the datagrams it dropped (a full buffer) with each read.
  setsockopt(socket.fd(), SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof one);
  setsockopt(socket.fd(), SOL_SOCKET, SO_RCVBUF, &kReceiveBufferBytes, sizeof kReceiveBufferBytes);
  return socket;
}

}  // namespace

GrsimPort::GrsimPort(MessageBus& bus, const ChannelNames& channels, GrsimOptions options)
    : bus_(bus),
      channels_(channels),
      options_(std::move(options)),
      socket_(open_port(options_)),
      buffer_(kMaxDatagramBytes + 1),
      book_(std::chrono::duration_cast<Clock::duration>(
          std::chrono::duration<double>(options_.command_hold))) {
  ubersim::subscribe(
      bus_, channels_, topics::kSimState,
      [this](const sim_state_t& s) {
        if (!state_.update(s)) ++counters_["states dropped (sim time not valid)"];
      },
      10);
  ubersim::subscribe(bus_, channels_, topics::kSimControlAck,
                     [this](const sim_control_ack_t& a) { on_ack(a); });
  for (Team team : kTeams) {
    ubersim::subscribe(bus_, channels_, topics::kRadioFeedback.of(team),
                       [this, team](const radio_feedback_t& f) { on_feedback(team, f); });
  }
}

void GrsimPort::gate(std::vector<Team> timed_teams, PublishTimed publish, ProgramOf program_of) {
  timed_teams_ = std::move(timed_teams);
  publish_timed_ = std::move(publish);
  program_of_ = std::move(program_of);
  gated_ = !timed_teams_.empty();
}

bool GrsimPort::timed(Team team) const {
  return std::find(timed_teams_.begin(), timed_teams_.end(), team) != timed_teams_.end();
}

// A timed team's status follows the group's sim time: its feedback waits until
// the group reaches the time it was sent (drain_timed).
void GrsimPort::on_feedback(Team team, const radio_feedback_t& feedback) {
  if (gated_ && timed(team)) {
    held_feedback_.emplace_back(team, feedback);
    return;
  }
  apply_feedback(team, feedback);
}

// The robots' status takes the feedback in; the book says whether a robot's kick fired.
void GrsimPort::apply_feedback(Team team, const radio_feedback_t& feedback) {
  status_.on_feedback(team, feedback, [this, team](int32_t id) { return book_.kick(team, id); });
}

void GrsimPort::start() {
  spdlog::info(
      "grSim protocol: grSim_Packet on {}:{}; robot status to the sender's address, ports {} "
      "(blue) and {} (yellow); a team silent for {} s stops{}",
      options_.listen_address, options_.port, options_.blue_status_port,
      options_.yellow_status_port, options_.command_hold,
      options_.command_hold > 0 ? "" : " never (--grsim-command-hold 0)");
  for (Team team : timed_teams_) {
    spdlog::info(
        "grSim protocol: the {} team's program runs under the time shim: its grSim commands are "
        "read at the team group's quiescences and stamped with its sim time; other colours' "
        "grSim commands are dropped while it runs",
        team_name(team));
  }
  bus_.watch(socket_.fd(), [this] { on_readable(); });
}

void GrsimPort::on_readable() {
  const Clock::time_point now = Clock::now();
  for (int i = 0; i < kGrsimDatagramsPerWakeup; ++i) {
    if (!receive_one(now, Arrival::RealTime)) break;
  }
  flush(now);
}

bool GrsimPort::receive_one(Clock::time_point now, Arrival arrival) {
  sockaddr_in from{};
  iovec io{buffer_.data(), buffer_.size()};
  alignas(cmsghdr) char control[CMSG_SPACE(sizeof(std::uint32_t))];
  msghdr message{};
  message.msg_name = &from;
  message.msg_namelen = sizeof from;
  message.msg_iov = &io;
  message.msg_iovlen = 1;
  message.msg_control = control;
  message.msg_controllen = sizeof control;
  const ssize_t size = recvmsg(socket_.fd(), &message, MSG_DONTWAIT);
  if (size < 0) return false;  // EAGAIN: drained
  for (cmsghdr* c = CMSG_FIRSTHDR(&message); c != nullptr; c = CMSG_NXTHDR(&message, c)) {
    if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL) {
      std::uint32_t drops = 0;
      std::copy_n(reinterpret_cast<const char*>(CMSG_DATA(c)), sizeof drops,
                  reinterpret_cast<char*>(&drops));
      if (drops != kernel_drops_) {
        counters_["grSim datagrams lost in a full socket buffer"] += drops - kernel_drops_;
        bad_input_.warn("grsim_overflow",
                        "grSim datagrams arrive faster than the bridge reads them: the "
                        "kernel dropped some");
        kernel_drops_ = drops;
      }
    }
  }
  handle_datagram(buffer_.data(), static_cast<std::size_t>(size), from, now, arrival);
  return true;
}

bool GrsimPort::drain_timed(std::int64_t now_ns, double settled) {
  if (!gated_) return false;
  // The book's clock is the group's sim time from here on.
  const Clock::time_point now{
      std::chrono::duration_cast<Clock::duration>(std::chrono::nanoseconds(now_ns))};
  const double t = static_cast<double>(now_ns) / 1e9;
  const double known = std::min(t, settled + kReleaseEpsilon);
  using Held = std::pair<Team, radio_feedback_t>;
  for (const Held& held :
       take_until(held_feedback_, known, [](const Held& h) { return h.second.t_sent; })) {
    apply_feedback(held.first, held.second);
  }
  // The group is quiescent: what waits is finite (a bound against a flood from outside).
  statuses_sent_ = false;
  constexpr int kMostPerDrain = 1 << 16;
  for (int i = 0; i < kMostPerDrain && receive_one(now, Arrival::AtQuiescence); ++i) {
  }
  for (Team team : timed_teams_) {
    std::optional<radio_packet_t> packet;
    if (book_.has_news(team)) {
      packet = book_.packet(team, now);
    } else {
      packet = book_.due(team, now, kGrsimRepeatInterval);  // a repeat, or the silent team's stop
    }
    if (!packet) continue;
    packet->t_sent = t;
    publish_timed_(team, std::move(*packet));
    ++counters_[std::string("grSim radio packets ") + team_name(team) + " (timed)"];
  }
  return statuses_sent_;
}

void GrsimPort::release_replacements() {
  held_replacements_.release(program_of_,
                             [this](const grSim_Replacement& replacement, const sockaddr_in&) {
                               handle_replacement(replacement);
                             });
}

void GrsimPort::stop_gating() {
  if (!gated_) return;
  release_replacements();
  gated_ = false;
  for (const auto& [team, feedback] : held_feedback_) apply_feedback(team, feedback);
  held_feedback_.clear();
  spdlog::info("grSim protocol: the team programs ended; the port follows real time again");
}

void GrsimPort::handle_datagram(const std::uint8_t* data, std::size_t size, const sockaddr_in& from,
                                Clock::time_point now, Arrival arrival) {
  ++counters_["grSim datagrams"];
  grSim_Packet packet;
  Errors errors;
  // grSim takes a packet with required fields missing as far as it goes.
  if (size > kMaxDatagramBytes || !decode_datagram(data, size, packet, errors, true).ok) {
    ++counters_["grSim datagrams dropped (malformed or too large)"];
    bad_input_.warn("grsim_malformed",
                    "dropped a datagram on the grSim port: " +
                        (errors.empty() ? std::string() : errors.back().message()));
    return;
  }
  if (!errors.empty()) count_errors(errors, "unknown fields");
  if (packet.has_commands()) handle_commands(packet.commands(), now, arrival);
  if (packet.has_replacement()) {
    // A timed team's replacement goes to physics with the next frame (release_replacements).
    const bool held = gated_ && arrival == Arrival::AtQuiescence &&
                      held_replacements_.hold(packet.replacement(), from);
    if (!held) handle_replacement(packet.replacement());
  }
  // grSim answers each datagram with the robots whose status changed, to its sender.
  if (status_.pending() && send_status(from)) statuses_sent_ = true;
}

bool GrsimPort::refused_while_gated(Team team, Arrival arrival) {
  if (!gated_) return false;
  const std::string name = team_name(team);
  if (!timed(team)) {
    ++counters_["grSim command packets dropped (" + name +
                " is not a grSim team under the time shim)"];
    bad_input_.warn("grsim_not_timed_" + name,
                    "dropped a grSim command packet for " + name +
                        ": while the bridge runs team programs under the time shim, only their "
                        "grSim-protocol colours take grSim commands (docs/timeshim.md)");
    return true;
  }
  if (arrival == Arrival::RealTime) {
    // The group sends only while the bridge runs it, and it drains the port
    // at each of its quiescences: this one came from a program outside it.
    ++counters_["grSim command packets dropped (" + name + ", from outside the team group)"];
    bad_input_.warn("grsim_outside_" + name, "dropped a grSim command packet for " + name +
                                                 " from a program outside the team group (the " +
                                                 name +
                                                 " team's program runs under the time shim)");
    return true;
  }
  return false;
}

void GrsimPort::handle_commands(const grSim_Commands& commands, Clock::time_point now,
                                Arrival arrival) {
  const Team team =
      commands.has_isteamyellow() && commands.isteamyellow() ? Team::Yellow : Team::Blue;
  if (refused_while_gated(team, arrival)) return;
  book_.heard(team, now);
  Errors errors;
  for (const grSim_Robot_Command& in : commands.robot_commands()) {
    if (!in.has_id() || in.id() >= kGrsimMaxRobots) {
      ++counters_["grSim robot commands dropped (no id, or id beyond 15)"];
      bad_input_.warn("grsim_id", "dropped a grSim robot command without an id below 16");
      continue;
    }
    const auto id = static_cast<int32_t>(in.id());
    const std::optional<GrsimRobotCommand> command =
        translate_grsim_robot_command(in, options_.translation, book_.last(team, id), errors);
    if (command) {
      book_.put(team, *command, now);
      ++counters_[std::string("grSim robot commands ") + team_name(team)];
    }
  }
  if (!errors.empty()) count_errors(errors, "robot commands dropped");
}

void GrsimPort::handle_replacement(const grSim_Replacement& replacement) {
  ++counters_["grSim replacements"];
  Errors errors;
  const SimulatorCommand command = grsim_replacement_command(replacement, state_.get(), errors);
  SimControlTranslation translation =
      translate_simulator_command(command, state_.get(), options_.sim_control);
  errors.insert(errors.end(), translation.errors.begin(), translation.errors.end());
  for (sim_control_t& request : translation.requests) {
    request.request_id = next_request_id_++;
    request.sender = kGrsimSender;
    ubersim::publish(bus_, channels_, topics::kSimControl, request);
    ++counters_["grSim SIM_CONTROL requests"];
  }
  if (!errors.empty()) count_errors(errors, "replacement parts not applied");
}

void GrsimPort::count_errors(const Errors& errors, const std::string& what) {
  counters_["grSim " + what] += errors.size();
  bad_input_.warn("grsim_" + what, "grSim port, " + what + ": " + errors.front().message());
}

void GrsimPort::on_ack(const sim_control_ack_t& ack) {
  if (ack.sender != kGrsimSender || ack.ok) return;
  ++counters_["grSim SIM_CONTROL requests refused by physics"];
  bad_input_.warn("grsim_refused", "physics refused a grSim replacement: " + ack.message);
}

bool GrsimPort::send_status(const sockaddr_in& sender) {
  bool sent = false;
  for (Team team : kTeams) {
    const std::optional<Robots_Status> changes = status_.changes(team);
    if (!changes) continue;
    sockaddr_in to = sender;
    to.sin_port = htons(static_cast<uint16_t>(team == Team::Blue ? options_.blue_status_port
                                                                 : options_.yellow_status_port));
    std::string bytes;
    changes->SerializeToString(&bytes);
    if (socket_.send_to(bytes, to)) {
      ++counters_[std::string("grSim status packets ") + team_name(team)];
      sent = true;
    } else {
      bad_input_.warn("grsim_status_send", "could not send a grSim robot status packet");
    }
  }
  return sent;
}

void GrsimPort::publish(Team team, radio_packet_t packet) {
  const auto t = static_cast<std::size_t>(team);
  packet.sequence = ++sequence_[t];
  packet.t_sent = state_.sim_time();
  ubersim::publish(bus_, channels_, topics::kRadio.of(team), packet);
  ++counters_[std::string("grSim radio packets ") + team_name(team)];
}

void GrsimPort::flush(Clock::time_point now) {
  if (gated_) return;  // timed teams' packets go out at the group's quiescences
  for (Team team : kTeams) {
    const auto t = static_cast<std::size_t>(team);
    if (book_.has_news(team) && now - last_publish_[t] >= kGrsimPublishInterval) {
      last_publish_[t] = now;
      publish(team, book_.packet(team, now));
    }
  }
}

void GrsimPort::tick(Clock::time_point now) {
  if (gated_) return;
  flush(now);
  for (Team team : kTeams) {
    if (std::optional<radio_packet_t> due = book_.due(team, now, kGrsimRepeatInterval)) {
      publish(team, std::move(*due));
    }
  }
}

std::optional<GrsimPort::Clock::time_point> GrsimPort::next_wake() const {
  if (gated_) return std::nullopt;
  std::optional<Clock::time_point> next;
  auto sooner = [&next](Clock::time_point t) { next = next ? std::min(*next, t) : t; };
  for (Team team : kTeams) {
    const auto t = static_cast<std::size_t>(team);
    if (book_.has_news(team)) sooner(last_publish_[t] + kGrsimPublishInterval);
    if (const std::optional<Clock::time_point> due = book_.next_due(team, kGrsimRepeatInterval)) {
      sooner(*due);
    }
  }
  return next;
}

void GrsimPort::log_summary() const {
  std::string text;
  for (const auto& [name, count] : counters_) text += " " + name + "=" + std::to_string(count);
  for (Team team : kTeams) {
    text += fmt::format(
        " grSim commands superseded {0}={1} grSim stops (team silent {2} s) {0}={3}",
        team_name(team), book_.superseded(team), options_.command_hold, book_.stops(team));
  }
  spdlog::info("grSim summary:{}", text);
}

}  // namespace ubersim::ssl
