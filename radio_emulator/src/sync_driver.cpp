#include "ubersim/radio/sync_driver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <optional>

#include "ubersim/spdlog.hpp"

namespace ubersim::radio {

namespace {

// Who holds physics back when no client owes an answer: the next frame (the log's name).
constexpr const char* kNextFrame = "vision";
// Who holds it at a state the feedback links must see first (timed clients).
constexpr const char* kFeedback = "radio feedback";

}  // namespace

SyncDriver::SyncDriver(MessageBus& bus, const ChannelNames& channels, RadioEmulator& emulator,
                       SyncOptions options, Publish publish)
    : publish_horizon_(bus, channels, topics::kSyncHorizon),
      publish_status_(bus, channels, topics::kSyncStatus),
      emulator_(emulator),
      options_(options),
      publish_(std::move(publish)),
      coordinator_(options.client_timeout) {
  emulator_.set_sync(true);
  horizon_.horizon = -1;
}

void SyncDriver::on_client(const sync_client_t& message, Clock::time_point now) {
  const std::string change = coordinator_.on_client(message);
  if (change.empty()) return;
  clients_changed();
  // A rejoin ends a degraded stretch: as loud as the drop.
  if (change.rfind("sync client rejoined", 0) == 0) {
    spdlog::warn("{}", change);
  } else {
    spdlog::info("{}", change);
  }
  publish_status(now);
  update(true, now);
}

void SyncDriver::on_schedule(const vision_schedule_t& schedule, Clock::time_point now) {
  coordinator_.on_schedule(schedule, now);
  update(true, now);
}

void SyncDriver::on_packet(Team team, const radio_packet_t& packet, Clock::time_point now) {
  const auto answer = coordinator_.on_answer(team, packet.t_sent, now);
  switch (answer.verdict) {
    case SyncCoordinator::Verdict::Unregistered:
      log_.warn(std::string("unregistered:") + team_name(team),
                std::string("ignored a ") + team_name(team) +
                    " radio packet: in sync mode only a registered client's answers count "
                    "(SYNC_CLIENT, docs/sync.md)");
      return;
    case SyncCoordinator::Verdict::Unmatched:
      log_.warn(std::string("unmatched:") + team_name(team),
                std::string("ignored a ") + team_name(team) + " radio packet with t_sent " +
                    std::to_string(packet.t_sent) +
                    " s: no unanswered frame was captured then (duplicate or out of order)");
      return;
    case SyncCoordinator::Verdict::Accepted:
      break;
  }
  if (emulator_.has_sim_time()) {
    publish_(emulator_.on_answer(team, packet, answer.t_arrival));
  } else if (held_.size() < kMaxHeldAnswers) {
    held_.push_back({team, packet, answer.t_arrival});
  } else {
    ++held_dropped_;
    log_.warn("held", fmt::format("dropped a {} radio packet sent at {:.6f} s: more than {} "
                                  "came before physics' first state",
                                  team_name(team), packet.t_sent, kMaxHeldAnswers));
  }
  update(false, now);
}

// Answers held for the first state go to the emulator right after it, in the
// order they came: which robots they may command is known only now.
void SyncDriver::on_sim_state(const sim_state_t& state, Clock::time_point now) {
  publish_(emulator_.on_sim_state(state, now));
  if (emulator_.has_sim_time()) {
    for (const HeldAnswer& held : held_) {
      publish_(emulator_.on_answer(held.team, held.packet, held.t_arrival));
    }
    held_.clear();
  }
  // The feedback links saw this state: physics may go on past it.
  update(false, now);
}

double SyncDriver::earliest_arrival(Team team) const {
  double arrival = coordinator_.earliest_arrival(team);
  for (const HeldAnswer& held : held_) {
    if (held.team == team) arrival = std::min(arrival, held.t_arrival);
  }
  return arrival;
}

// A timed client answers every state, so while one is in, the emulator's
// feedback goes with physics' steps (RadioEmulator::set_feedback_in_step).
void SyncDriver::clients_changed() {
  emulator_.set_feedback_in_step(coordinator_.has_timed_client());
}

bool SyncDriver::tick(Clock::time_point now) {
  forgive_own_stall(now);
  const auto dropped = coordinator_.expire(now);
  for (const Drop& drop : dropped) {
    if (options_.strict) {
      spdlog::error("{}: failing the run (--sync-strict)", drop.describe());
      return false;
    }
    spdlog::warn("{}; the run goes on without it", drop.describe());
  }
  if (!dropped.empty()) clients_changed();
  if (!dropped.empty() || now - last_status_ >= kStatusRepeat) publish_status(now);
  update(!dropped.empty() || now - last_published_ >= kHorizonRepeat, now);
  return true;
}

void SyncDriver::forgive_own_stall(Clock::time_point now) {
  const auto gap = now - last_tick_;
  const bool first = last_tick_ == Clock::time_point{};
  last_tick_ = now;
  if (first || gap <= kStall) return;
  coordinator_.forgive(gap);
  ++stalls_;
  const double seconds = std::chrono::duration<double>(gap).count();
  stalled_seconds_ += seconds;
  log_.warn("stall", fmt::format("sync: the radio emulator did not run for {:.3f} s of wall time "
                                 "(a loaded or paused machine): that time does not count "
                                 "against the clients' --sync-timeout",
                                 seconds));
}

// Sent before the horizon that lets physics past a drop, on the same socket:
// a listener hears of the drop before any state after it.
void SyncDriver::publish_status(Clock::time_point now) {
  const std::int64_t sequence = status_.sequence + 1;
  status_ = coordinator_.status();
  status_.sequence = sequence;
  publish_status_(status_);
  last_status_ = now;
}

std::int8_t SyncDriver::hold(Clock::time_point now) {
  if (now >= next_hold_log_) {
    next_hold_log_ = now + std::chrono::seconds(5);
    spdlog::info("sync: physics holds: waiting for {}",
                 started_ ? std::string("the vision emulator")
                          : std::to_string(options_.expected_clients - coordinator_.clients()) +
                                " more client(s) on SYNC_CLIENT");
  }
  return started_ ? sync_horizon_t::HELD_BY_NEXT_FRAME : sync_horizon_t::HELD_BY_REGISTRATION;
}

void SyncDriver::update(bool always_publish, Clock::time_point now) {
  double horizon = std::numeric_limits<double>::infinity();
  double answered_until = std::numeric_limits<double>::infinity();
  std::int8_t held_by = sync_horizon_t::HELD_BY_NOTHING;
  std::string bound;
  if (!started_ && coordinator_.clients() >= options_.expected_clients) {
    started_ = true;
    spdlog::info("sync: {} client(s) registered, physics may run", coordinator_.clients());
  }
  if (!started_ || !coordinator_.schedule_heard()) {
    // Physics holds where it is until every expected client can see the
    // first frame, so that runs start alike.
    horizon = 0;
    answered_until = 0;
    held_by = hold(now);
    if (held_by == sync_horizon_t::HELD_BY_NEXT_FRAME) bound = kNextFrame;
  } else {
    for (Team team : kTeams) {
      const double arrival = earliest_arrival(team);
      answered_until = std::min(answered_until, coordinator_.answered_until(team));
      RadioEmulator::SyncRelease release = emulator_.sync_release(team, arrival);
      publish_(release.out);
      // A timed client's bridge hands physics the team's simulation control
      // commands with the next frame, which physics must wait at: it may not
      // run past the promise by the link's latency (docs/sync.md).
      if (coordinator_.timed(team)) release.horizon = std::min(release.horizon, arrival);
      if (release.horizon < horizon) {
        horizon = release.horizon;
        const std::optional<std::string> client = coordinator_.bound_by(team);
        held_by = client ? sync_horizon_t::HELD_BY_CLIENT : sync_horizon_t::HELD_BY_NEXT_FRAME;
        bound = client.value_or(kNextFrame);
      }
    }
    if (emulator_.feedback_in_step() && emulator_.feedback_due() < horizon) {
      horizon = emulator_.feedback_due();
      held_by = sync_horizon_t::HELD_BY_FEEDBACK;
      bound = kFeedback;
    }
  }
  if (!always_publish && horizon == horizon_.horizon && held_by == horizon_.held_by &&
      bound == horizon_.waiting_for && answered_until == horizon_.answered_until) {
    return;
  }
  if (!released_ && held_by != sync_horizon_t::HELD_BY_REGISTRATION) {
    released_ = true;
    if (before_release_) before_release_();
  }
  // Physics must know which state to publish before it may step to it.
  if (before_horizon_) before_horizon_(now);
  ++horizon_.sequence;
  horizon_.horizon = horizon;
  horizon_.answered_until = answered_until;
  horizon_.held_by = held_by;
  horizon_.waiting_for = bound;
  horizon_.clients = coordinator_.clients();
  publish_horizon_(horizon_);
  last_published_ = now;
}

void SyncDriver::log_summary() const {
  const SyncStats& s = coordinator_.stats();
  spdlog::info(
      "sync: {} frames scheduled, {} answers; ignored: {} from unregistered teams, {} duplicated "
      "or out of order; {} client timeouts, {} registrations refused; the radio emulator stalled "
      "{} times ({:.3f} s of wall time not counted against the clients); {} answers dropped "
      "before physics' first state",
      s.frames, s.answers, s.unregistered, s.unmatched, s.timeouts, s.refused, stalls_,
      stalled_seconds_, held_dropped_);
  for (const SyncClientStats& c : coordinator_.client_stats()) {
    spdlog::info(
        "sync client '{}': {} answers, {} frames skipped, answer time mean {:.3f} ms, slowest "
        "{:.3f} ms (wall)",
        c.name, c.answers, c.frames_skipped,
        c.answers ? 1e3 * c.answer_wall_seconds / static_cast<double>(c.answers) : 0.0,
        1e3 * c.slowest_answer);
  }
  // The line tools/launch.sh prints at the end of a run (docs/sync.md, "A dropped client").
  const std::string summary = coordinator_.summary();
  if (coordinator_.stats().timeouts > 0) {
    spdlog::warn("{}", summary);
  } else {
    spdlog::info("{}", summary);
  }
}

}  // namespace ubersim::radio
