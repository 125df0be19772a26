#include "ubersim/radio/feedback_link.hpp"

#include <algorithm>
#include <limits>

namespace ubersim::radio {
namespace {
constexpr double kNoSampleYet = -std::numeric_limits<double>::infinity();
}

FeedbackLink::FeedbackLink(const RadioProfile& profile, Team team, std::uint64_t seed)
    : profile_(profile),
      team_(team),
      random_(seed, team, Direction::Feedback),
      next_sample_(kNoSampleYet) {}

void FeedbackLink::reset() {
  next_sample_ = kNoSampleYet;
  grid_origin_ = 0;
  in_flight_.clear();
}

std::vector<radio_feedback_t> FeedbackLink::on_sim_state(const sim_state_t& state) {
  const double now = state.sim_time;
  if (profile_.feedback_rate > 0 && now + kTimeEpsilon >= next_sample_) {
    const double period = 1.0 / profile_.feedback_rate;
    // Keep the phase while physics steps finer than the period; start afresh
    // after a gap (first state, or steps coarser than the period).
    if (now < next_sample_ + period) {
      next_sample_ += period;
    } else {
      next_sample_ = grid_origin_ = now + period;
    }
    sample(state);
  }
  std::vector<radio_feedback_t> due;
  for (auto& [release_time, feedback] : in_flight_.pop_due(now + kTimeEpsilon)) {
    // The delivery time itself, not the state's that noticed it: the same
    // whichever states physics publishes (it may publish only some on demand).
    feedback.t_sent = release_time;
    ++stats_.delivered;
    due.push_back(std::move(feedback));
  }
  return due;
}

double FeedbackLink::next_due() const {
  if (profile_.feedback_rate <= 0 && in_flight_.empty()) {
    return std::numeric_limits<double>::infinity();
  }
  if (next_sample_ == kNoSampleYet) return 0.0;
  double due = profile_.feedback_rate > 0 ? next_sample_ : std::numeric_limits<double>::infinity();
  if (!in_flight_.empty()) due = std::min(due, in_flight_.front_release());
  return due;
}

double FeedbackLink::sample_phase() const {
  return next_sample_ == kNoSampleYet ? 0.0 : grid_origin_;
}

void FeedbackLink::sample(const sim_state_t& state) {
  radio_feedback_t feedback;
  feedback.team = static_cast<std::int8_t>(team_);
  feedback.t_measured = state.sim_time;
  feedback.t_sent = 0;
  bool any_robot = false;
  for (const auto& robot : state.robots) {
    if (robot.team != static_cast<int>(team_)) continue;
    any_robot = true;
    robot_feedback_t report;
    report.robot_id = robot.robot_id;
    report.ball_contact = robot.ball_contact;
    report.kicker_charged = robot.kicker_charged;
    feedback.robots.push_back(report);
  }
  if (!any_robot) return;  // no robot of this team to report
  ++stats_.sampled;
  if (random_.happens(profile_.feedback.packet_loss)) {
    ++stats_.lost_packets;
    return;
  }
  std::vector<robot_feedback_t> kept;
  for (const auto& report : feedback.robots) {
    if (random_.happens(profile_.feedback.robot_loss)) {
      ++stats_.lost_reports;
      continue;
    }
    kept.push_back(report);
  }
  feedback.robots = std::move(kept);
  feedback.num_robots = static_cast<std::int32_t>(feedback.robots.size());
  in_flight_.push(state.sim_time + random_.delay(profile_.feedback), std::move(feedback));
}

}  // namespace ubersim::radio
