#include "ubersim/referee/autoref_shell.hpp"

#include <chrono>
#include <cmath>
#include <iostream>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/referee_t.hpp>
#include <ubersim/sync_status_t.hpp>
#include <vector>

#include "ubersim/config.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/process_host.hpp"
#include "ubersim/referee/event_log.hpp"
#include "ubersim/referee/referee_message.hpp"
#include "ubersim/referee/robot_radii.hpp"
#include "ubersim/referee/sim_link.hpp"
#include "ubersim/referee/state_judge.hpp"
#include "ubersim/topics.hpp"

namespace ubersim::referee {
namespace {

constexpr std::int64_t kRequestBase = 7LL << 56;  // our request ids, apart from the CLI's
// Who the referee is to physics: the sender of its requests and placements,
// the consumer of its truth demand.
constexpr const char* kName = "ubersim_referee auto";

std::vector<char> encoded(const field_geometry_t& geometry) {
  std::vector<char> bytes(static_cast<std::size_t>(geometry.getEncodedSize()));
  geometry.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// Every size the rules and placements use is a length a field can have.
bool usable(const field_geometry_t& f) {
  for (double length : {f.field_length, f.field_width, f.boundary_width, f.boundary_width_goal_line,
                        f.goal_width, f.penalty_area_depth, f.penalty_area_width,
                        f.center_circle_radius, f.penalty_mark_distance}) {
    if (!std::isfinite(length) || length < 0 || length > 1e6) return false;
  }
  return f.field_length > 0 && f.field_width > 0 && std::isfinite(f.ball_radius) &&
         f.ball_radius > 0 && f.ball_radius < 1;
}

// The referee's shell: the StateJudge core on the host (subscriptions, the
// truth demand, REFEREE and placements out, the event log, the result line).
class AutoRefShell {
 public:
  AutoRefShell(const AutoOptions& options, ProcessHost& host)
      : options_(options), host_(host), log_(options.events_file) {}

  int run() {
    start();
    // Physics (ground truth on demand, its default) sends only the states someone asked for.
    // In sync mode physics stops at the state the referee judges next
    // (REFEREE.next_judge_time) and sends it: that is the referee's demand.
    // Otherwise physics does not wait for the referee, which then needs every
    // state to see the ones it judges.
    if (!options_.sync) host_.ask_for_truth(every_step_demand());
    // Stopped before the game is over (a signal): the result says so.
    host_.at_stop([this] {
      if (!over_) finish();
    });
    return host_.run(std::chrono::milliseconds(100));
  }

 private:
  // The field, the judge, the subscriptions, physics resumed (--start): the
  // referee listens once it logs its first line.
  void start() {
    MessageBus& bus = host_.bus();
    const ChannelNames& channels = host_.channels();
    const std::chrono::milliseconds timeout(static_cast<long>(options_.timeout_s * 1000));
    SimLink link(bus, channels, kName);
    field_ = link.geometry(timeout);
    new_judge();
    ubersim::subscribe(
        bus, channels, topics::kSimState, [this](const sim_state_t& s) { on_state(s); }, 100000);
    // In sync mode the radio emulator says which teams lost control: the result says so.
    ubersim::subscribe(bus, channels, topics::kSyncStatus,
                       [this](const sync_status_t& s) { on_sync_status(s); });
    // Before the first STOP the referee waits for the teams (--team-wait): who commands robots.
    if (options_.game.team_wait > 0) {
      for (Team team : kTeams) {
        ubersim::subscribe_unhurried(
            bus, channels, topics::kRadio.of(team),
            [this, team](const radio_packet_t&) { judge_->team_heard(team); });
      }
    }
    // Physics announces its field now and then and at once after a SET_FIELD.
    ubersim::subscribe(bus, channels, topics::kSimGeometry,
                       [this](const field_geometry_t& g) { on_geometry(g); });
    if (options_.start_physics) {
      // Physics waited paused for us: the game starts at the first state we see.
      sim_control_t resume{};
      resume.action = sim_control_t::RESUME;
      const auto ack = link.request(resume, timeout);
      if (!ack.ok) throw std::runtime_error("physics refused to resume: " + ack.message);
    }
    ubersim::subscribe(bus, channels, topics::kSimControlAck, [](const sim_control_ack_t& ack) {
      if (ack.request_id >= kRequestBase && !ack.ok)
        spdlog::warn("physics refused a placement: {}", ack.message);
    });
    spdlog::info(
        "automatic referee: field {}, game {} s in {} half(s), yellow '{}' against blue "
        "'{}', publishing on {}{}",
        field_.name, options_.game.game_length, options_.game.halves, options_.game.yellow_name,
        options_.game.blue_name, channel_name(channels, topics::kReferee),
        options_.sync ? " after every state (sync)" : "");
  }

  // A judge that has seen nothing: its first state starts a game.
  void new_judge() {
    judge_.emplace(
        JudgeOptions{options_.game, options_.sides, options_.sync, options_.judge_every_step},
        field_, [this](const std::string& type) { return radii_(type); });
  }

  // --repeat: kNewGamePause after a game ended (or at once after a reset of the
  // simulation), the next one starts from this state, 0 : 0.
  bool start_next_game(const sim_state_t& state) {
    const double ended = judge_->last_time();
    if (!options_.repeat || !std::isfinite(state.sim_time) ||
        (state.sim_time < ended + kNewGamePause && state.sim_time >= ended)) {
      return false;
    }
    new_judge();
    over_ = false;
    started_ = false;
    ++game_number_;
    spdlog::info("automatic referee: game {} starts at {:.2f} s", game_number_, state.sim_time);
    return true;
  }

  // Between games (--repeat) the final state stays on REFEREE at the rate it
  // has during a game, for whoever listens (a bridge forwarding it to SSL teams).
  void keep_final_state_up(const sim_state_t& state) {
    constexpr double kPeriod = 0.1;  // s of sim time, as StateJudge publishes
    if (!last_referee_ || !std::isfinite(state.sim_time) ||
        state.sim_time < last_referee_->sim_time + kPeriod) {
      return;
    }
    last_referee_->sim_time = state.sim_time;
    last_referee_->next_judge_time = state.sim_time + kPeriod;
    ubersim::publish(host_.bus(), host_.channels(), topics::kReferee, *last_referee_);
  }

  void on_geometry(const field_geometry_t& geometry) {
    if (encoded(geometry) == encoded(field_)) return;
    if (!usable(geometry)) {
      bad_input_.warn("field_geometry", "a SIM_GEOMETRY with sizes that are not finite lengths");
      return;
    }
    field_ = geometry;
    judge_->set_field(field_);
    spdlog::info(
        "automatic referee: field now {} x {} m (penalty mark {} m from the goal "
        "attacked, walls {} m behind the goal lines)",
        field_.field_length, field_.field_width, field_.penalty_mark_distance,
        field_.boundary_width_goal_line);
  }

  void on_sync_status(const sync_status_t& status) {
    for (int i = 0; i < 2; ++i) {
      if (!std::isfinite(status.dropped_at[i]) || !std::isfinite(status.without_control[i]) ||
          status.without_control[i] < 0 || status.drops[i] < 0) {
        bad_input_.warn("sync_status",
                        "ignored a SIM_SYNC_STATUS with a time that is not finite or a count "
                        "below 0");
        return;
      }
    }
    if (status.sequence < sync_status_.sequence) return;  // an older one, or another sender's
    sync_status_ = status;
  }

  void on_state(const sim_state_t& state) {
    if (over_ && !start_next_game(state)) {
      if (options_.repeat) keep_final_state_up(state);
      return;
    }
    const std::uint64_t refused = judge_->refused();
    auto out = judge_->on_state(state);
    if (judge_->refused() > refused) {
      bad_input_.warn("state_not_finite",
                      "not judged: a SIM_STATE with a sim time that is not valid or a number "
                      "not finite or beyond 1e9");
    }
    if (!out.judged) return;
    if (!started_) {
      started_ = true;
      wall_start_ = host_.now();
    }
    for (const std::string& line : out.log_lines) log_.write(line);
    if (out.placement) {
      out.placement->request_id = kRequestBase + next_request_++;
      out.placement->sender = kName;
      ubersim::publish(host_.bus(), host_.channels(), topics::kSimControl, *out.placement);
    }
    if (out.referee) {
      ubersim::publish(host_.bus(), host_.channels(), topics::kReferee, *out.referee);
      last_referee_ = std::move(out.referee);
    }
    if (!out.game_over) return;
    finish();
    // The run ends once the handlers of this wakeup are done, before the next turn.
    if (options_.exit_at_end && !options_.repeat) host_.stop(0);
  }

  void finish() {
    over_ = true;
    const double wall =
        started_ ? std::chrono::duration<double>(host_.now() - wall_start_).count() : 0.0;
    const RefereeState empty;
    const auto& s = judge_ ? judge_->state() : empty;
    const double last_time = judge_ ? judge_->last_time() : 0.0;
    const auto losses = control_losses(sync_status_, last_time);
    log_.write(result_line(s, last_time, wall, losses));
    // One line, the one tools/launch.sh shows: a degraded result says so on it.
    const std::string degraded = degraded_text(losses);
    std::cout << "result: yellow " << s.yellow.goals << " : " << s.blue.goals << " blue ("
              << (s.game_over ? "game over" : "stopped") << " at " << last_time << " s sim time, "
              << wall << " s wall time, " << (judge_ ? judge_->judged() : 0) << " states judged)"
              << (degraded.empty() ? "" : ", " + degraded) << std::endl;
  }

  const AutoOptions& options_;
  ProcessHost& host_;
  EventLog log_;
  field_geometry_t field_{};
  sync_status_t sync_status_{};  // the latest; all zero (nobody dropped) until one arrives
  std::optional<StateJudge> judge_;
  std::optional<referee_t> last_referee_;            // the newest published
  RobotRadii radii_{options_.common.config_root()};  // robot types from SIM_STATE
  std::int64_t next_request_ = 0;
  ThrottledLog bad_input_;
  bool started_ = false;
  bool over_ = false;
  int game_number_ = 1;
  ProcessHost::Clock::time_point wall_start_;
};

}  // namespace

int run_auto_referee(const AutoOptions& options) {
  ProcessHost host(options.common, kName);
  AutoRefShell shell(options, host);
  return shell.run();
}

}  // namespace ubersim::referee
