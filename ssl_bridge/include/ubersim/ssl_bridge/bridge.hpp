#pragma once
// The bridge process' core: LCM on one side, SSL protocol UDP sockets on the
// other, one thread, one poll loop.
#include <netinet/in.h>

#include <array>
#include <chrono>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/vision_schedule_t.hpp>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/process_host.hpp"
#include "ubersim/ssl_bridge/held_for_next_frame.hpp"
#include "ubersim/ssl_bridge/latest_state.hpp"
#include "ubersim/ssl_bridge/lcm_team_door.hpp"
#include "ubersim/ssl_bridge/multicast_out.hpp"
#include "ubersim/ssl_bridge/official_referee.hpp"
#include "ubersim/ssl_bridge/referee_translation.hpp"
#include "ubersim/ssl_bridge/robot_control_translation.hpp"
#include "ubersim/ssl_bridge/sim_control_translation.hpp"
#include "ubersim/ssl_bridge/sync_answers.hpp"
#include "ubersim/ssl_bridge/team_group.hpp"
#include "ubersim/ssl_bridge/tracked_frames.hpp"
#include "ubersim/ssl_bridge/udp_socket.hpp"
#include "ubersim/ssl_bridge/vision_translation.hpp"
#include "ubersim/sync_client.hpp"

namespace ubersim::ssl {

struct BridgeOptions {
  // Where the multicast streams go (multicast_out.hpp): each on the interfaces
  // listed (addresses, or "default": where the kernel routes the group) with
  // its TTL. local_only: every stream on lo (127.0.0.1) with TTL 0, whatever
  // the interface and TTL settings say.
  bool local_only = false;
  std::string vision_address = "224.5.23.2";  // multicast group (or a unicast address)
  int vision_port = 10020;
  int vision_ttl = 1;  // grSim's and ssl-vision's; 0: never leaves the host
  std::string vision_interface = "default,127.0.0.1";
  std::string listen_address = "127.0.0.1";  // control and robot control sockets
  int control_port = 10300;
  int blue_port = 10301;
  int yellow_port = 10302;
  double ack_timeout = 1.0;  // s of wall time to wait for physics before answering anyway
  SimControlSettings sim_control;
  std::optional<WheelMapping> wheels;
  GeometryExtras geometry;
  // Tracked frames (--tracked): TrackerWrapperPacket from ground truth.
  bool tracked = false;
  std::string tracked_address = "224.5.23.2";
  int tracked_port = 10010;
  int tracked_ttl = 1;
  std::string tracked_interface;  // empty: vision_interface
  double tracked_rate = 60;       // Hz of sim time
  // Referee messages (from REFEREE, the automatic referee), where the SSL game
  // controller sends them. With official_referee the direction turns: the
  // official game controller's messages there go to REFEREE, and nothing of
  // ubersim's is sent. Without it, a foreign game controller heard there stops
  // ubersim's messages (one referee per group), with an error in the log.
  std::string referee_address = "224.5.23.1";
  int referee_port = 10003;
  int referee_ttl = 1;
  std::string referee_interface;  // empty: vision_interface; also where the bridge listens
  bool official_referee = false;
  // What robot specs start from (the --robot-type file); unset: specs are refused.
  std::optional<BaseRobotType> base_robot_type;
  // Sync mode (--sync, docs/sync.md): each team that speaks to its robot
  // control port becomes a sync client, and each of its RobotControl
  // datagrams answers the oldest detection frame it has not answered yet.
  bool sync = false;
  // The tracked frames' uuid and the referee's source_identifier: random, as
  // a real source's; with a seed, the same on every run (make_uuid).
  std::optional<std::uint64_t> id_seed;
  double sync_timeout = 1.0;  // s of wall time a team may take to answer a frame
  // Team programs the bridge starts under the time shim (--team-command, sync
  // mode only): each such team is a *timed* sync client (docs/timeshim.md,
  // "Integration with sync mode"); everything the bridge sends is gated by sim time.
  TeamGroupOptions teams;
  // Which of them speak LCM, on a private bus (--team-protocol, lcm_team_door.hpp).
  LcmDoorOptions lcm_door;
};

// A packet held back for a timed team until the sim time it stands for.
struct StampedPacket {
  double t;  // s of sim time
  std::string bytes;
};

// The settings of the vision, tracked frames and referee streams.
StreamSettings vision_stream(const BridgeOptions& options);
StreamSettings tracked_stream(const BridgeOptions& options);
StreamSettings referee_stream(const BridgeOptions& options);

// Driven by the program's process host (main.cpp): the host's loop reads the
// bus and the bridge's sockets (watched on the bus), tick() runs after every
// wakeup (at least every 50 ms), stop() once at the end.
class SslBridge {
 public:
  // On the program's host: its bus, channels and truth demand (the tracked
  // frames' rate).
  SslBridge(ProcessHost& host, BridgeOptions options);
  // Logs where everything goes and watches the sockets on the bus.
  void start();
  // After every wakeup: answers what physics did not acknowledge in time;
  // sync mode: drops teams past their timeout, says the registered ones again.
  void tick(std::chrono::steady_clock::time_point now);
  // Sync mode: the registered teams leave.
  void stop();
  void log_summary() const;
  // Timed teams: another door of the team group (the grSim port): `drain` at
  // each quiescence (true when it sent something to the group, which then
  // runs again at the same instant), `ended` once the team programs ended.
  // `settled` (s of sim time): every feedback and referee message stamped up
  // to it is here, on every run (latest_before, timed_inputs.hpp). `at_frame`
  // when a frame goes to the group, before the group runs on (physics waits
  // at the frame's state then).
  using TimedDrain = std::function<bool(std::int64_t now_ns, double settled)>;
  void add_timed_door(TimedDrain drain, std::function<void()> at_frame,
                      std::function<void()> ended);
  // A timed team's radio packet (t_sent set): numbered in the team's sequence,
  // with its promises; held until the team registered.
  void publish_timed_radio(Team team, radio_packet_t packet);
  // Which team program (the order of --team-command) sent from this address;
  // the number of programs for another sender (held_for_next_frame.hpp).
  std::size_t program_of(const sockaddr_in& from);

 private:
  struct PendingResponse {
    sockaddr_in client{};
    std::map<int64_t, bool> awaiting;  // request ids not yet acknowledged
    SimulatorResponse response;
    std::chrono::steady_clock::time_point deadline;
  };

  void on_vision(const vision_frame_t& frame);
  void on_geometry(const vision_geometry_t& geometry);
  void on_ack(const sim_control_ack_t& ack);
  void on_state(const sim_state_t& state);
  void on_referee(const referee_t& referee);
  // A Referee datagram heard on the referee group (ours come back too).
  void on_referee_datagram(const std::vector<uint8_t>& bytes);
  // decode_datagram, counting and logging (once per second) what it drops.
  bool decoded(const std::vector<uint8_t>& bytes, google::protobuf::Message& message,
               Errors& errors, const std::string& port);
  void handle_control_datagram(const std::vector<uint8_t>& bytes, const sockaddr_in& from);
  void handle_robot_datagram(Team team, const std::vector<uint8_t>& bytes, const sockaddr_in& from);
  void send_vision(const SSL_WrapperPacket& packet);
  // Where each multicast stream goes (start()): the first place to look when
  // a team's program hears nothing.
  void log_destinations() const;
  // Sync mode: registration and goodbye on SYNC_CLIENT (sync_clients_), and
  // the team's frame bookkeeping; sync_datagram() says what a robot control
  // datagram answers (nullopt: it answers no frame and goes nowhere).
  std::optional<double> sync_datagram(Team team);
  void sync_tick(std::chrono::steady_clock::time_point now);
  void drop_sync_client(Team team, const std::string& why);
  void sync_leave();
  // Timed teams (team_group.hpp): outputs wait for the sim time they stand
  // for; the group runs ahead to the next input between them.
  bool timed(Team team) const;
  bool timed_mode() const { return teams_ != nullptr; }
  void on_schedule(const vision_schedule_t& schedule);
  // A state physics published with vision frames, or without (one that a
  // truth demand asked for).
  enum class StateKind { WithFrames, WithoutFrames };
  void deliver_timed(StateKind kind);
  void register_timed_teams();
  void send_timed_geometry();
  void remember_state_time(double sim_time);
  bool timed_teams_joined() const;
  // A team program's simulation control command, kept for the next frame
  // (apply_timed_controls) when the teams are timed and registered.
  bool held_for_next_frame(const std::vector<uint8_t>& bytes, const sockaddr_in& from);
  void apply_timed_controls();
  void run_teams_to(double t);
  bool at_quiescence(std::int64_t now_ns);
  void promise(std::int64_t promise_ns);
  void teams_ended();
  double group_time() const;
  // Largest radius of the robots on the field (their types' radii), else the configured one.
  double max_robot_radius() const;
  void answer(PendingResponse& pending);
  void expire_pending(std::chrono::steady_clock::time_point now);

  ProcessHost& host_;
  MessageBus& bus_;
  ChannelNames channels_;
  BridgeOptions options_;
  MulticastStream vision_out_;
  UdpSocket control_socket_;
  UdpSocket blue_socket_;
  UdpSocket yellow_socket_;
  LatestState state_;  // the newest SIM_STATE with a valid sim time
  std::map<Team, radio_feedback_t> feedback_;
  std::map<std::string, double> type_radius_;      // m, robot type name -> radius
  std::optional<field_geometry_t> current_field_;  // from the latest VISION_GEOMETRY
  MulticastStream referee_out_;
  std::string referee_source_;  // our source_identifier, to tell our packets from others'
  RefereeTranslator referee_translator_;
  std::optional<UdpSocket> referee_listener_;
  OfficialRefereeTracker official_referee_;
  bool foreign_referee_heard_ = false;
  std::optional<TrackedFrames> tracked_;
  std::optional<MulticastStream> tracked_out_;
  std::map<int64_t, std::shared_ptr<PendingResponse>> pending_by_request_;
  int64_t next_request_id_ = 1;
  std::array<int64_t, 2> radio_sequence_{};  // per team: each RADIO_<TEAM> on its own
  std::array<SyncAnswers, 2> sync_;          // by Team
  std::array<SyncClient, 2> sync_clients_;   // by Team: ssl_bridge_<team> on SYNC_CLIENT
  ThrottledLog bad_input_;
  std::map<std::string, uint64_t> counters_;
  // Ground truth at the tracked rate (tracked frames); without them the
  // bridge takes whatever states the others ask for (docs/sync.md).
  std::unique_ptr<TeamGroup> teams_;
  std::vector<Team> timed_teams_;  // the colours the team group's programs play
  // By Team: what a timed team sent before it registered (at sim time 0).
  std::array<std::vector<radio_packet_t>, 2> timed_early_;
  std::unique_ptr<LcmTeamDoor> lcm_door_;  // the timed teams that speak LCM
  struct TimedDoor {
    TimedDrain drain;
    std::function<void()> at_frame;
    std::function<void()> ended;
  };
  std::vector<TimedDoor> timed_doors_;     // add_timed_door
  std::vector<std::string> timed_vision_;  // vision packets waiting for their publication
  bool teams_up_ = false;                  // the group was quiescent once
  std::string timed_geometry_;             // the latest geometry packet
  std::string timed_geometry_sent_;        // the one the teams got last
  double timed_geometry_next_ = 0;         // s, sim time it is sent again
  std::vector<StampedPacket> timed_referee_;
  std::vector<StampedPacket> timed_tracked_;
  std::int64_t timed_step_ = -1;  // of the latest schedule heard
  double timed_publication_ = 0;  // s, sim time the awaited frames are published at
  double timed_next_input_ = 0;   // s, the next frame's earliest publication
  double timed_captured_ = 0;     // s, the latest capture time of the frames heard
  int timed_frames_due_ = 0;      // frames of the latest schedule not heard yet
  // The team programs' simulation control commands since the last frame (apply_timed_controls).
  HeldForNextFrame<std::vector<uint8_t>> timed_controls_;
  // Sim times of the latest states physics published, oldest first.
  std::deque<double> timed_state_times_;
  // s: every referee and feedback message stamped up to it is here
  // (latest_before, timed_inputs.hpp), as of the latest delivery.
  double timed_settled_ = -1;
};

}  // namespace ubersim::ssl
