#include "ubersim/ssl_bridge/bridge.hpp"

#include <google/protobuf/stubs/logging.h>

#include <algorithm>
#include <array>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/team_t.hpp>

#include "ubersim/ssl_bridge/datagram_decoding.hpp"
#include "ubersim/topics.hpp"

namespace ubersim::ssl {
namespace {

// make_uuid's purposes: the two ids of one seed differ.
constexpr std::uint64_t kRefereeId = 1;
constexpr std::uint64_t kTrackedId = 2;

constexpr const char* kSender = "ubersim_ssl_bridge";
// Datagrams taken from each socket per wakeup: a flood on one port cannot
// starve LCM, the other ports or the shutdown signal.
constexpr int kDatagramsPerWakeup = 64;

template <class Handle>
void drain(UdpSocket& socket, const Handle& handle) {
  sockaddr_in from{};
  for (int i = 0; i < kDatagramsPerWakeup; ++i) {
    auto bytes = socket.receive(from);
    if (!bytes) break;
    handle(*bytes, from);
  }
}

// SIM_CONTROL requests waiting for physics at once; a command arriving beyond
// that is answered at once with an error, so a flood of commands costs neither
// memory nor physics' time. (One command is a few requests; robot specs for
// every robot of a team are the most, ~2 per spec.)
constexpr std::size_t kMaxPendingRequests = 256;

int8_t team_code(Team team) {
  return team == Team::Yellow ? int8_t{team_t::YELLOW} : int8_t{team_t::BLUE};
}

// One stream's settings; --local-only overrides the interfaces and TTL.
StreamSettings stream(const BridgeOptions& options, const std::string& name,
                      const std::string& group, int port, int ttl, const std::string& interfaces) {
  StreamSettings s;
  s.name = name;
  s.group = group;
  s.port = port;
  s.ttl = options.local_only ? 0 : ttl;
  s.interfaces = options.local_only ? "127.0.0.1" : interfaces;
  if (s.interfaces.empty()) s.interfaces = options.vision_interface;
  return s;
}

}  // namespace

StreamSettings vision_stream(const BridgeOptions& options) {
  return stream(options, "vision", options.vision_address, options.vision_port, options.vision_ttl,
                options.vision_interface);
}

StreamSettings tracked_stream(const BridgeOptions& options) {
  return stream(options, "tracked frames", options.tracked_address, options.tracked_port,
                options.tracked_ttl, options.tracked_interface);
}

StreamSettings referee_stream(const BridgeOptions& options) {
  return stream(options, "referee messages", options.referee_address, options.referee_port,
                options.referee_ttl, options.referee_interface);
}

SslBridge::SslBridge(ProcessHost& host, BridgeOptions options)
    : host_(host),
      bus_(host.bus()),
      channels_(host.channels()),
      options_(std::move(options)),
      vision_out_(vision_stream(options_)),
      control_socket_(UdpSocket::bound(options_.listen_address, options_.control_port)),
      blue_socket_(UdpSocket::bound(options_.listen_address, options_.blue_port)),
      yellow_socket_(UdpSocket::bound(options_.listen_address, options_.yellow_port)),
      referee_out_(referee_stream(options_)),
      referee_source_("ubersim-" + make_uuid(options_.id_seed, kRefereeId)),
      referee_translator_(referee_source_),
      sync_{{SyncAnswers(options_.sync_timeout), SyncAnswers(options_.sync_timeout)}},
      sync_clients_{{SyncClient(bus_, channels_, Team::Yellow, "ssl_bridge_yellow"),
                     SyncClient(bus_, channels_, Team::Blue, "ssl_bridge_blue")}} {
  // protobuf logs every datagram that misses a required field to stderr, one
  // line each, at any rate; decoded() counts and logs them throttled instead.
  google::protobuf::SetLogHandler(nullptr);
  if (options_.base_robot_type) {
    options_.sim_control.base_robot_type = &*options_.base_robot_type;
    type_radius_[options_.base_robot_type->config.name] = options_.base_robot_type->config.radius;
  }
  ubersim::subscribe(bus_, channels_, topics::kVision,
                     [this](const vision_frame_t& f) { on_vision(f); });
  ubersim::subscribe(bus_, channels_, topics::kVisionGeometry,
                     [this](const vision_geometry_t& g) { on_geometry(g); });
  if (options_.tracked) {
    TrackedSettings settings;
    settings.rate = options_.tracked_rate;
    settings.ball_model = options_.geometry.ball_model;
    settings.uuid = make_uuid(options_.id_seed, kTrackedId);
    tracked_.emplace(settings);
    tracked_out_.emplace(tracked_stream(options_));
    host_.ask_for_truth(periodic_demand(options_.tracked_rate));
  }
  ubersim::subscribe(
      bus_, channels_, topics::kSimState, [this](const sim_state_t& s) { on_state(s); }, 10);
  ubersim::subscribe(bus_, channels_, topics::kSimControlAck,
                     [this](const sim_control_ack_t& a) { on_ack(a); });
  try {
    // Joined where the referee stream goes: a game controller on this host
    // or the network sends on its default interface.
    std::vector<std::string> addresses;
    for (const OutInterface& out : referee_out_.interfaces()) addresses.push_back(out.address);
    std::vector<std::string> failed;
    referee_listener_.emplace(UdpSocket::multicast_receiver(
        options_.referee_address, options_.referee_port, addresses, failed));
    for (const std::string& failure : failed) {
      spdlog::warn("referee group: {}: a game controller sending there goes unnoticed", failure);
    }
  } catch (const std::exception& e) {
    if (options_.official_referee) throw;  // the official referee is what was asked for
    spdlog::warn("cannot listen on the referee group ({}): a game controller there goes unnoticed",
                 e.what());
  }
  if (options_.official_referee) {
    spdlog::info("official referee: Referee messages on {}:{} go to {}; ubersim sends none",
                 options_.referee_address, options_.referee_port,
                 channel_name(channels_, topics::kReferee));
  } else {
    ubersim::subscribe(bus_, channels_, topics::kReferee,
                       [this](const referee_t& r) { on_referee(r); });
  }
  for (Team team : kTeams) {
    ubersim::subscribe(bus_, channels_, topics::kRadioFeedback.of(team),
                       [this, team](const radio_feedback_t& f) { feedback_[team] = f; });
  }
  if (!options_.teams.commands.empty()) {
    teams_ = std::make_unique<TeamGroup>(options_.teams);
    for (const TeamCommand& command : options_.teams.commands) {
      timed_teams_.push_back(command.team);
      if (command.both) timed_teams_.push_back(Team::Blue);
    }
    for (Team team : timed_teams_) sync_clients_[static_cast<int>(team)].set_timed(true);
    ubersim::subscribe(bus_, channels_, topics::kVisionSchedule,
                       [this](const vision_schedule_t& s) { on_schedule(s); });
  }
  if (teams_ && !options_.lcm_door.teams.empty()) {
    lcm_door_ = std::make_unique<LcmTeamDoor>(
        bus_, channels_, options_.lcm_door, [this](Team team, radio_packet_t& packet) {
          packet.sequence = ++radio_sequence_[static_cast<int>(team)];
          ubersim::publish(bus_, channels_, topics::kRadio.of(team), packet);
        });
  }
}

void SslBridge::send_vision(const SSL_WrapperPacket& packet) {
  std::string bytes;
  packet.SerializeToString(&bytes);
  if (timed_mode() && !teams_->exited()) {
    timed_vision_.push_back(std::move(bytes));  // sent at its publication (deliver_timed)
    return;
  }
  if (vision_out_.send(bytes)) {
    ++counters_["vision packets sent"];
  } else {
    bad_input_.warn("vision_send", "could not send a vision packet");
  }
}

void SslBridge::on_vision(const vision_frame_t& frame) {
  const bool last_of_step = timed_mode() && timed_frames_due_ > 0 && --timed_frames_due_ == 0;
  if (timed_mode()) timed_captured_ = std::max(timed_captured_, frame.t_capture);
  if (!forwardable(frame)) {
    ++counters_["vision frames dropped (not finite)"];
    bad_input_.warn("vision_not_finite",
                    "dropped a VISION frame with a number not finite or beyond 1e9");
  } else {
    send_vision(detection_packet(frame));
  }
  if (lcm_door_ && !teams_->exited() && forwardable(frame)) lcm_door_->hold(frame);
  if (last_of_step) deliver_timed(StateKind::WithFrames);
  if (!forwardable(frame)) return;
  // Owed before the team can answer: the answer comes back through our own poll loop.
  if (options_.sync) {
    const auto now = std::chrono::steady_clock::now();
    for (Team team : kTeams) {
      if (sync_[static_cast<int>(team)].on_frame(frame.t_capture, now)) {
        drop_sync_client(team, "owes " + std::to_string(SyncAnswers::kMaxOwed) + " frames");
      }
    }
  }
  // Tracked frames wait as long as this frame did: capture -> now (sim time).
  // Timed teams get them with the detections of the same instant instead
  // (deliver_timed): how far physics is ahead of this frame depends on timing.
  if (tracked_ && !timed_mode() && state_.get() && state_.sim_time() >= frame.t_capture) {
    tracked_->set_latency(std::min(1.0, state_.sim_time() - frame.t_capture));
  }
}

void SslBridge::on_state(const sim_state_t& state) {
  if (!state_.update(state)) {
    ++counters_["states dropped (sim time not finite, negative or beyond 1e9 s)"];
    bad_input_.warn("state_bad_time",
                    "dropped a SIM_STATE whose sim time is not finite, negative or beyond 1e9 s");
    return;
  }
  if (timed_mode()) remember_state_time(state.sim_time);
  if (!tracked_) return;
  const std::uint64_t refused = tracked_->refused();
  const auto packets = tracked_->on_state(state);
  if (tracked_->refused() > refused) {
    ++counters_["states without tracked frames (not finite)"];
    bad_input_.warn("state_not_finite",
                    "no tracked frame from a SIM_STATE with a number not finite or beyond 1e9");
  }
  for (const TrackerWrapperPacket& packet : packets) {
    std::string bytes;
    packet.SerializeToString(&bytes);
    if (timed_mode() && !teams_->exited()) {
      timed_tracked_.push_back({state.sim_time, std::move(bytes)});
      continue;
    }
    if (tracked_out_->send(bytes)) {
      ++counters_["tracked packets sent"];
    } else {
      bad_input_.warn("tracked_send", "could not send a tracked packet");
    }
  }
}

void SslBridge::on_referee(const referee_t& referee) {
  if (foreign_referee_heard_) {
    ++counters_["referee packets held back (another game controller sends)"];
    return;
  }
  std::string bytes;
  referee_translator_.translate(referee).SerializeToString(&bytes);
  if (timed_mode() && !teams_->exited()) {
    timed_referee_.push_back({referee.sim_time, std::move(bytes)});
    return;
  }
  if (referee_out_.send(bytes)) {
    ++counters_["referee packets sent"];
  } else {
    bad_input_.warn("referee_send", "could not send a referee packet");
  }
}

void SslBridge::on_referee_datagram(const std::vector<uint8_t>& bytes) {
  Referee referee;
  Errors errors;
  if (!decoded(bytes, referee, errors, "referee")) return;
  if (referee.source_identifier() == referee_source_) return;  // our own, looped back
  if (!options_.official_referee) {
    if (!foreign_referee_heard_) {
      spdlog::error(
          "another game controller ('{}') sends Referee messages to {}:{}: ubersim's REFEREE is "
          "no longer sent there; start the bridge with --official-referee (launch.sh --referee "
          "official) to forward that game controller to {} instead",
          referee.source_identifier(), options_.referee_address, options_.referee_port,
          channel_name(channels_, topics::kReferee));
    }
    foreign_referee_heard_ = true;
    ++counters_["foreign referee packets heard"];
    return;
  }
  ubersim::publish(bus_, channels_, topics::kReferee,
                   official_referee_.translate(referee, state_.get()));
  ++counters_["official referee packets forwarded"];
}

double SslBridge::max_robot_radius() const {
  double largest = 0;
  if (const sim_state_t* state = state_.get()) {
    for (const robot_state_t& robot : state->robots) {
      const auto found = type_radius_.find(robot.robot_type);
      if (found != type_radius_.end()) largest = std::max(largest, found->second);
    }
  }
  return largest > 0 ? largest : options_.geometry.max_robot_radius;
}

void SslBridge::on_geometry(const vision_geometry_t& geometry) {
  if (!forwardable(geometry)) {
    ++counters_["vision geometry dropped (not finite or out of range)"];
    bad_input_.warn("geometry_not_finite",
                    "dropped a VISION_GEOMETRY with a number not finite or out of range; the "
                    "last good geometry stays");
    return;
  }
  current_field_ = geometry.field;
  GeometryExtras extras = options_.geometry;
  if (extras.max_robot_radius > 0) extras.max_robot_radius = max_robot_radius();
  if (timed_mode() && !teams_->exited()) {
    // The vision emulator repeats its geometry on a wall-time timer; timed
    // teams get it at sim-time instants instead (deliver_timed).
    geometry_packet(geometry, extras).SerializeToString(&timed_geometry_);
    register_timed_teams();
    return;
  }
  send_vision(geometry_packet(geometry, extras));
}

void SslBridge::on_ack(const sim_control_ack_t& ack) {
  if (ack.sender != kSender) return;
  const auto found = pending_by_request_.find(ack.request_id);
  if (found == pending_by_request_.end()) return;
  const std::shared_ptr<PendingResponse> pending = found->second;
  pending_by_request_.erase(found);
  pending->awaiting.erase(ack.request_id);
  if (!ack.ok) {
    SimulatorError* error = pending->response.add_errors();
    error->set_code(kErrorPhysics);
    error->set_message("physics refused the request: " + ack.message);
  }
  if (pending->awaiting.empty()) answer(*pending);
  if (teams_ && pending_by_request_.empty()) register_timed_teams();
}

void SslBridge::answer(PendingResponse& pending) {
  std::string bytes;
  pending.response.SerializeToString(&bytes);
  control_socket_.send_to(bytes, pending.client);
  ++counters_["control responses"];
}

void SslBridge::expire_pending(std::chrono::steady_clock::time_point now) {
  for (auto it = pending_by_request_.begin(); it != pending_by_request_.end();) {
    const std::shared_ptr<PendingResponse> pending = it->second;
    if (now < pending->deadline) {
      ++it;
      continue;
    }
    // Answer once for the whole command, naming what physics never acknowledged.
    for (auto& [id, unused] : pending->awaiting) pending_by_request_.erase(id);
    SimulatorError* error = pending->response.add_errors();
    error->set_code(kErrorNoAnswer);
    error->set_message("physics did not acknowledge in time; is ubersim_physics running?");
    pending->awaiting.clear();
    answer(*pending);
    it = pending_by_request_.begin();
  }
  if (teams_ && pending_by_request_.empty()) register_timed_teams();
}

bool SslBridge::decoded(const std::vector<uint8_t>& bytes, google::protobuf::Message& message,
                        Errors& errors, const std::string& port) {
  const DecodedDatagram result = decode_datagram(bytes.data(), bytes.size(), message, errors);
  if (!result.ok) {
    ++counters_[port + " datagrams dropped (malformed or too large)"];
    bad_input_.warn(port, "dropped a datagram on the " + port + " port: " +
                              (errors.empty() ? std::string() : errors.back().message()));
    return false;
  }
  if (result.unknown_fields > 0) {
    counters_[port + " unknown fields dropped"] += result.unknown_fields;
    bad_input_.warn(port + "_unknown",
                    "dropped fields ubersim does not know on the " + port + " port");
  }
  return true;
}

void SslBridge::handle_control_datagram(const std::vector<uint8_t>& bytes,
                                        const sockaddr_in& from) {
  ++counters_["control datagrams"];
  auto pending = std::make_shared<PendingResponse>();
  pending->client = from;
  Errors errors;
  SimulatorCommand command;
  if (pending_by_request_.size() >= kMaxPendingRequests) {
    ++counters_["control datagrams refused (busy)"];
    bad_input_.warn("control_busy",
                    "simulation control commands arrive faster than physics answers");
    add_error(errors, kErrorBusy,
              std::to_string(pending_by_request_.size()) +
                  " requests already wait for physics; this command was not applied");
  } else if (decoded(bytes, command, errors, "control")) {
    options_.sim_control.current_field = current_field_ ? &*current_field_ : nullptr;
    SimControlTranslation translation =
        translate_simulator_command(command, state_.get(), options_.sim_control);
    errors.insert(errors.end(), translation.errors.begin(), translation.errors.end());
    for (const DefinedRobotType& type : translation.defined_types) {
      options_.sim_control.spec_types.record(type);
      type_radius_[type.name] = type.radius;
      spdlog::info("robot specs: robot type {} (radius {} m)", type.name, type.radius);
    }
    if (translation.realism) {
      translation.realism->request_id = next_request_id_++;
      translation.realism->sender = kSender;
      ubersim::publish(bus_, channels_, topics::kEmulatorRealism, *translation.realism);
      ++counters_["realism changes"];
    }
    if (translation.cameras) {
      translation.cameras->request_id = next_request_id_++;
      translation.cameras->sender = kSender;
      ubersim::publish(bus_, channels_, topics::kVisionCameras, *translation.cameras);
      ++counters_["camera sets"];
      spdlog::info("cameras from the geometry's calibrations: {} camera(s)",
                   translation.cameras->num_cameras);
    }
    if (translation.vision_port) {
      vision_out_.set_port(*translation.vision_port);
      spdlog::info("vision now sent to port {}", *translation.vision_port);
    }
    for (sim_control_t& request : translation.requests) {
      request.request_id = next_request_id_++;
      request.sender = kSender;
      pending->awaiting[request.request_id] = true;
      pending_by_request_[request.request_id] = pending;
      ubersim::publish(bus_, channels_, topics::kSimControl, request);
    }
  }
  for (const SimulatorError& error : errors) *pending->response.add_errors() = error;
  pending->deadline = std::chrono::steady_clock::now() +
                      std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                          std::chrono::duration<double>(options_.ack_timeout));
  if (pending->awaiting.empty()) answer(*pending);
}

void SslBridge::handle_robot_datagram(Team team, const std::vector<uint8_t>& bytes,
                                      const sockaddr_in& from) {
  const std::string name = team_name(team);
  ++counters_[name + " robot control datagrams"];
  // Sync mode: every datagram answers a frame (or is a hello or an extra one),
  // whatever it holds, so a malformed one still counts as "nothing to send".
  // A timed team (under the time shim) is stamped with the sim time it sent at.
  std::optional<double> answers;
  if (timed(team)) {
    answers = group_time();
  } else if (options_.sync) {
    answers = sync_datagram(team);
  }
  RobotControlResponse response;
  Errors errors;
  RobotControl control;
  radio_packet_t packet{};
  packet.team = team_code(team);
  if (decoded(bytes, control, errors, name + " robot control")) {
    RobotControlTranslation translation = translate_robot_control(control, team, options_.wheels);
    errors.insert(errors.end(), translation.errors.begin(), translation.errors.end());
    packet = std::move(translation.packet);
  }
  // Outside sync mode nothing to say means no packet on the radio; in sync
  // mode the empty packet is the answer "nothing to send" (docs/sync.md).
  const bool publish = options_.sync ? answers.has_value() : packet.num_commands > 0;
  if (publish) {
    packet.t_sent = answers.value_or(state_.sim_time());
    if (timed(team)) {
      publish_timed_radio(team, std::move(packet));
    } else {
      packet.sequence = ++radio_sequence_[static_cast<int>(team)];
      ubersim::publish(bus_, channels_, topics::kRadio.of(team), packet);
    }
  }
  for (const SimulatorError& error : errors) *response.add_errors() = error;
  const auto feedback = feedback_.find(team);
  add_feedback(feedback == feedback_.end() ? nullptr : &feedback->second, response);
  std::string out;
  response.SerializeToString(&out);
  (team == Team::Blue ? blue_socket_ : yellow_socket_).send_to(out, from);
}

std::optional<double> SslBridge::sync_datagram(Team team) {
  const std::string name = team_name(team);
  const SyncAnswers::Datagram datagram = sync_[static_cast<int>(team)].on_datagram();
  switch (datagram.kind) {
    case SyncAnswers::Kind::Registered: {
      SyncClient& client = sync_clients_[static_cast<int>(team)];
      spdlog::info("sync: the {} team spoke on its port: registered as sync client {}", name,
                   client.name());
      // Physics starts stepping once the teams are registered: it must know the
      // tracked frames' instants before, or two sync runs publish other states.
      // (A team speaks only after a detection packet, so physics listens by now.)
      const auto now = std::chrono::steady_clock::now();
      host_.send_truth_demand(now);
      client.join(now);
      return std::nullopt;
    }
    case SyncAnswers::Kind::Extra:
      ++counters_[name + " robot control datagrams answering no frame (ignored)"];
      bad_input_.warn(name + "_sync_extra",
                      "ignored a " + name +
                          " RobotControl: every detection frame sent had its answer already "
                          "(sync mode: one RobotControl per detection packet)");
      return std::nullopt;
    case SyncAnswers::Kind::Answer:
      break;
  }
  return datagram.t_capture;
}

void SslBridge::sync_tick(std::chrono::steady_clock::time_point now) {
  for (Team team : kTeams) {
    if (sync_[static_cast<int>(team)].expire(now)) {
      drop_sync_client(team, "did not answer a detection frame within " +
                                 std::to_string(options_.sync_timeout) + " s of wall time");
    }
  }
  // Said again every second, for a radio emulator that starts later.
  for (SyncClient& client : sync_clients_) client.tick(now);
}

// Silent, no goodbye on SYNC_CLIENT (SyncClient::drop says why).
void SslBridge::drop_sync_client(Team team, const std::string& why) {
  sync_clients_[static_cast<int>(team)].drop();
  spdlog::warn("sync: the {} team {}: dropped (its next RobotControl registers it again)",
               team_name(team), why);
}

void SslBridge::sync_leave() {
  for (Team team : kTeams) {
    sync_[static_cast<int>(team)].leave();
    sync_clients_[static_cast<int>(team)].leave();  // nothing when it never joined
  }
}

void SslBridge::log_destinations() const {
  std::vector<const MulticastStream*> streams{&vision_out_};
  if (tracked_out_) streams.push_back(&*tracked_out_);
  if (!options_.official_referee) streams.push_back(&referee_out_);
  for (const MulticastStream* stream : streams) {
    for (const std::string& warning : stream->warnings()) spdlog::warn("{}", warning);
    spdlog::info("{}", stream->describe());
  }
  if (tracked_) spdlog::info("tracked frames at {} Hz of sim time", options_.tracked_rate);
  if (!options_.official_referee)
    spdlog::info("referee messages come from {}", channel_name(channels_, topics::kReferee));
  if (options_.local_only) {
    spdlog::info("--local-only: SSL multicast stays on this host (lo, ttl 0)");
  }
}

void SslBridge::start() {
  log_destinations();
  spdlog::info("simulation control {}:{}; robot control blue {}:{}, yellow {}:{}",
               options_.listen_address, options_.control_port, options_.listen_address,
               options_.blue_port, options_.listen_address, options_.yellow_port);
  bus_.watch(control_socket_.fd(), [this] {
    drain(control_socket_, [this](const std::vector<uint8_t>& bytes, const sockaddr_in& from) {
      if (!held_for_next_frame(bytes, from)) handle_control_datagram(bytes, from);
    });
  });
  bus_.watch(blue_socket_.fd(), [this] {
    drain(blue_socket_, [this](const std::vector<uint8_t>& bytes, const sockaddr_in& from) {
      handle_robot_datagram(Team::Blue, bytes, from);
    });
  });
  if (referee_listener_) {
    bus_.watch(referee_listener_->fd(), [this] {
      drain(*referee_listener_, [this](const std::vector<uint8_t>& bytes, const sockaddr_in&) {
        on_referee_datagram(bytes);
      });
    });
  }
  bus_.watch(yellow_socket_.fd(), [this] {
    drain(yellow_socket_, [this](const std::vector<uint8_t>& bytes, const sockaddr_in& from) {
      handle_robot_datagram(Team::Yellow, bytes, from);
    });
  });
  if (options_.sync) {
    spdlog::info(
        "sync mode: a team's first RobotControl registers it; then each RobotControl answers "
        "the oldest detection packet it has not answered (docs/sync.md)");
  }
  if (teams_) {
    teams_->start();
    run_teams_to(0);  // the teams start up at sim time 0, then register as timed clients
  }
}

void SslBridge::tick(std::chrono::steady_clock::time_point now) {
  expire_pending(now);
  if (options_.sync) sync_tick(now);
}

void SslBridge::stop() {
  if (options_.sync) sync_leave();
  if (teams_) teams_->stop();
}

void SslBridge::log_summary() const {
  std::string text;
  for (const auto& [name, count] : counters_) text += " " + name + "=" + std::to_string(count);
  if (options_.sync) {
    for (Team team : kTeams) {
      const SyncAnswerStats& s = sync_[static_cast<int>(team)].stats();
      text += std::string(" sync ") + team_name(team) + ": frames=" + std::to_string(s.frames) +
              " answers=" + std::to_string(s.answers) + " extra=" + std::to_string(s.extra) +
              " timeouts=" + std::to_string(s.timeouts + s.overflows);
    }
  }
  if (lcm_door_) text += lcm_door_->summary();
  if (teams_) {
    text += " team group: quiescences=" + std::to_string(teams_->quiescences()) +
            " advances=" + std::to_string(teams_->advances()) +
            " turns=" + std::to_string(teams_->turns()) +
            " (handed over=" + std::to_string(teams_->handoffs()) + ")" +
            " charged pauses=" + std::to_string(teams_->charged_pauses()) +
            " looks full=" + std::to_string(teams_->full_looks()) +
            " light=" + std::to_string(teams_->light_looks()) +
            " sim time=" + std::to_string(group_time()) + " s";
  }
  const std::uint64_t skipped = vision_out_.loopback_copies_skipped() +
                                (tracked_out_ ? tracked_out_->loopback_copies_skipped() : 0) +
                                referee_out_.loopback_copies_skipped();
  if (skipped > 0) {
    text += " lo copies not sent (a listener joined on the default interface hears those)=" +
            std::to_string(skipped);
  }
  spdlog::info("summary:{}; LCM messages dropped as malformed={}", text.empty() ? " nothing" : text,
               bus_.malformed_count());
}

}  // namespace ubersim::ssl
