// The SSL bridge with team programs under the time shim (docs/timeshim.md,
// "Integration with sync mode"): the bridge is the teams' clock. What it sends
// them waits for the sim time it stands for (a detection packet: its frame's
// publication), and what they send is stamped with the sim time they sent it.
#include <algorithm>
#include <cmath>
#include <ubersim/team_t.hpp>

#include "ubersim/spdlog.hpp"
#include "ubersim/ssl_bridge/bridge.hpp"
#include "ubersim/ssl_bridge/timed_inputs.hpp"
#include "ubersim/topics.hpp"

namespace ubersim::ssl {
namespace {

std::int64_t to_ns(double seconds) {
  return std::llround(seconds * 1e9);
}

// Sends the stamped packets up to t (s) in the order they came, keeps the rest.
template <class Send>
void send_until(std::vector<StampedPacket>& queue, double t, const Send& send) {
  const auto stamp = [](const StampedPacket& packet) { return packet.t; };
  for (const StampedPacket& due : take_until(queue, t, stamp)) send(due.bytes);
}

}  // namespace

bool SslBridge::timed(Team team) const {
  if (!teams_ || teams_->exited()) return false;
  return std::find(timed_teams_.begin(), timed_teams_.end(), team) != timed_teams_.end();
}

double SslBridge::group_time() const {
  return teams_ ? static_cast<double>(teams_->now_ns()) / 1e9 : 0.0;
}

// The vision emulator announces each step's frames before it sends them (one
// socket, in order), and the earliest publication of its next frame: the next
// input the team group can get, so the group may run ahead to it.
void SslBridge::on_schedule(const vision_schedule_t& schedule) {
  if (schedule.step <= timed_step_ || !(schedule.t_state >= 0) ||
      !(schedule.next_publication >= schedule.t_state)) {
    return;  // a repetition (or a reset: sim time of the group cannot go back)
  }
  timed_step_ = schedule.step;
  timed_publication_ = schedule.t_state;
  timed_next_input_ = schedule.next_publication;
  timed_frames_due_ = std::max(0, schedule.num_frames);
  if (timed_frames_due_ == 0) deliver_timed(StateKind::WithoutFrames);
}

// Every frame of the step is here: the group catches up to their publication,
// gets them (with the geometry, referee messages and tracked frames of that
// time), answers, and runs ahead to the next frame.
//
// Held simulation control commands go out only with frames: physics waits at
// a state with frames (the group promised nothing past their publication), so
// they apply there on every run. A state without frames (a capture instant,
// or one the radio's feedback links asked for) lies before the group's
// promise, and physics runs on from it while the commands travel: released
// there, a command applied at whichever step physics had reached (Utama-Core's
// start-up placements landed at steps 9 to 15 from run to run).
void SslBridge::deliver_timed(StateKind kind) {
  if (teams_->exited()) return;
  run_teams_to(timed_publication_);
  if (kind == StateKind::WithFrames) apply_timed_controls();
  timed_settled_ = std::max(timed_settled_, latest_before(timed_state_times_, timed_publication_));
  if (lcm_door_) lcm_door_->deliver(timed_publication_, timed_settled_);
  send_timed_geometry();
  for (const std::string& bytes : timed_vision_) {
    if (vision_out_.send(bytes)) ++counters_["vision packets sent"];
  }
  timed_vision_.clear();
  send_until(timed_referee_, timed_settled_, [this](const std::string& bytes) {
    if (referee_out_.send(bytes)) ++counters_["referee packets sent"];
  });
  if (tracked_out_) {
    // Tracked frames of the states up to the latest capture handed over: as
    // late as the detections, and the same on every run (every state up to a
    // frame's capture is here before the frame: physics sent it first).
    send_until(timed_tracked_, timed_captured_, [this](const std::string& bytes) {
      if (tracked_out_->send(bytes)) ++counters_["tracked packets sent"];
    });
  }
  run_teams_to(timed_next_input_);
}

void SslBridge::remember_state_time(double sim_time) {
  constexpr std::size_t kKept = 256;  // states between two deliveries, with room
  if (!timed_state_times_.empty() && sim_time < timed_state_times_.back()) {
    timed_state_times_.clear();  // physics was reset
  }
  timed_state_times_.push_back(sim_time);
  if (timed_state_times_.size() > kKept) timed_state_times_.pop_front();
}

// The geometry goes out when it changed, and again every second of sim time
// (what the vision emulator sends in wall time), always with a frame.
void SslBridge::send_timed_geometry() {
  constexpr double kRepeat = 1.0;  // s of sim time
  if (timed_geometry_.empty()) return;
  if (timed_geometry_ == timed_geometry_sent_ && timed_publication_ < timed_geometry_next_) return;
  if (vision_out_.send(timed_geometry_)) ++counters_["vision packets sent"];
  timed_geometry_sent_ = timed_geometry_;
  timed_geometry_next_ = timed_publication_ + kRepeat;
}

void SslBridge::run_teams_to(double t) {
  const bool running = teams_->run_to(
      to_ns(t), [this](std::int64_t now_ns) { return at_quiescence(now_ns); },
      [this](std::int64_t promise_ns) { promise(promise_ns); },
      [this] {
        // Called every 200 ms at most while the group runs, which may hold
        // this loop for seconds: physics forgets a demand not heard for 3 s,
        // and the tracked frames' states would then depend on wall time.
        host_.renew_truth_demand(std::chrono::steady_clock::now());
        return host_.stopping();
      });
  if (!running && teams_->exited()) teams_ended();
}

// Every thread of the group waits, so whatever it sent is in our sockets:
// stamp it with the group's time (handle_robot_datagram) and answer it.
// The teams register once their programs are up (the group's first
// quiescence: a team slow to start does not hold physics past its timeout) and
// the field's geometry is here, so that every run's first frame comes with it.
// A simulation control command the teams sent while they started (Utama-Core
// places every robot and the ball) is acknowledged first: physics, held at
// sim time 0 until they register, applies it there on every run.
void SslBridge::register_timed_teams() {
  if (!teams_up_ || timed_geometry_.empty() || !pending_by_request_.empty()) return;
  const auto now = std::chrono::steady_clock::now();
  for (Team team : timed_teams_) {
    SyncClient& client = sync_clients_[static_cast<int>(team)];
    if (client.joined()) continue;
    spdlog::info("sync: the {} team's program is up: registered as timed sync client {}",
                 team_name(team), client.name());
    host_.send_truth_demand(now);
    client.join(now);
    // What it sent while it started up, after its registration (same socket).
    for (const radio_packet_t& packet : timed_early_[static_cast<int>(team)]) {
      ubersim::publish(bus_, channels_, topics::kRadio.of(team), packet);
    }
    timed_early_[static_cast<int>(team)].clear();
  }
}

void SslBridge::add_timed_door(TimedDrain drain, std::function<void()> at_frame,
                               std::function<void()> ended) {
  timed_doors_.push_back({std::move(drain), std::move(at_frame), std::move(ended)});
}

void SslBridge::publish_timed_radio(Team team, radio_packet_t packet) {
  packet.sequence = ++radio_sequence_[static_cast<int>(team)];
  if (!sync_clients_[static_cast<int>(team)].joined()) {
    timed_early_[static_cast<int>(team)].push_back(std::move(packet));  // sent once it registered
    return;
  }
  ubersim::publish(bus_, channels_, topics::kRadio.of(team), packet);
}

bool SslBridge::timed_teams_joined() const {
  return std::all_of(timed_teams_.begin(), timed_teams_.end(),
                     [this](Team team) { return sync_clients_[static_cast<int>(team)].joined(); });
}

// A simulation control command a team sent during the game goes to physics
// with the next frame (held_for_next_frame.hpp; the radio holds physics at a
// timed team's promise, docs/sync.md "Timed clients").
void SslBridge::apply_timed_controls() {
  timed_controls_.release([this](const sockaddr_in& from) { return program_of(from); },
                          [this](const std::vector<uint8_t>& bytes, const sockaddr_in& from) {
                            handle_control_datagram(bytes, from);
                          });
  for (const TimedDoor& door : timed_doors_) door.at_frame();
}

// Also for one read outside a quiescence: a thread of the group can run
// while the bridge does not run the group (one Utama-Core run's start-up
// placements were read so; the cause was not found).
bool SslBridge::held_for_next_frame(const std::vector<uint8_t>& bytes, const sockaddr_in& from) {
  if (!timed_mode() || teams_->exited() || !timed_teams_joined()) return false;
  return timed_controls_.hold(bytes, from);
}

std::size_t SslBridge::program_of(const sockaddr_in& from) {
  return teams_ ? teams_->program_of_port(ntohs(from.sin_port)) : 0;
}

bool SslBridge::at_quiescence(std::int64_t now_ns) {
  bool answered = false;
  sockaddr_in from{};
  // Control commands before the registration are applied at sim time 0 (see
  // register_timed_teams); later ones at the state of the next frame (deliver_timed).
  while (auto bytes = control_socket_.receive(from)) {
    if (held_for_next_frame(*bytes, from)) continue;
    handle_control_datagram(*bytes, from);
    answered = true;
  }
  teams_up_ = true;
  register_timed_teams();
  if (lcm_door_) lcm_door_->drain(now_ns);  // RADIO_<TEAM> to the main bus, t_sent = now
  for (const TimedDoor& door : timed_doors_)
    answered = door.drain(now_ns, timed_settled_) || answered;
  for (Team team : kTeams) {
    UdpSocket& socket = team == Team::Blue ? blue_socket_ : yellow_socket_;
    while (auto bytes = socket.receive(from)) {
      handle_robot_datagram(team, *bytes, from);
      answered = true;  // its RobotControlResponse went back
    }
  }
  return answered;
}

// An empty radio packet at t_sent = the promise: nothing before it (docs/sync.md).
void SslBridge::promise(std::int64_t promise_ns) {
  for (Team team : timed_teams_) {
    if (!sync_clients_[static_cast<int>(team)].joined()) continue;
    radio_packet_t packet{};
    packet.team = team == Team::Yellow ? int8_t{team_t::YELLOW} : int8_t{team_t::BLUE};
    packet.sequence = ++radio_sequence_[static_cast<int>(team)];
    packet.t_sent = static_cast<double>(promise_ns) / 1e9;
    ubersim::publish(bus_, channels_, topics::kRadio.of(team), packet);
  }
}

// The team programs ended: their clients leave (the run goes on without
// them), and what was held back for them goes out now.
void SslBridge::teams_ended() {
  apply_timed_controls();
  if (lcm_door_) lcm_door_->stop_holding();
  for (const TimedDoor& door : timed_doors_) door.ended();
  for (Team team : timed_teams_) sync_clients_[static_cast<int>(team)].leave();
  if (!timed_geometry_.empty()) vision_out_.send(timed_geometry_);
  for (const std::string& bytes : timed_vision_) vision_out_.send(bytes);
  timed_vision_.clear();
  timed_referee_.clear();
  timed_tracked_.clear();
}

}  // namespace ubersim::ssl
