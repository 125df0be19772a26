#include "ubersim/ssl_bridge/tracked_frames.hpp"

#include <cmath>
#include <cstdio>
#include <random>
#include <ubersim/team_t.hpp>

#include "ubersim/sim_state_numbers.hpp"
#include "ubersim/ssl_bridge/units.hpp"

namespace ubersim::ssl {
namespace {

constexpr double kKickSpeedJump = 0.8;     // m/s within one state: a kick, not a push
constexpr double kKickerReach = 0.3;       // m, robot centre to ball for a kick to be its
constexpr double kStoppedSpeed = 0.05;     // m/s, the kicked ball has come to rest
constexpr std::size_t kMaxWaiting = 4096;  // states held back (bounded whatever the latency)

void set(Vector2& out, double x, double y) {
  out.set_x(static_cast<float>(x));
  out.set_y(static_cast<float>(y));
}

void set(Vector3& out, const double v[3]) {
  out.set_x(static_cast<float>(v[0]));
  out.set_y(static_cast<float>(v[1]));
  out.set_z(static_cast<float>(v[2]));
}

}  // namespace

std::string make_uuid(std::optional<std::uint64_t> seed, std::uint64_t purpose) {
  unsigned char b[16];
  if (seed) {
    // mt19937_64's output is the same on every standard library (a
    // distribution's is not): the bytes are taken from it directly.
    std::seed_seq sequence{static_cast<std::uint32_t>(*seed),
                           static_cast<std::uint32_t>(*seed >> 32),
                           static_cast<std::uint32_t>(purpose)};
    std::mt19937_64 engine(sequence);
    for (int half = 0; half < 2; ++half) {
      const std::uint64_t word = engine();
      for (int i = 0; i < 8; ++i) b[half * 8 + i] = static_cast<unsigned char>(word >> (8 * i));
    }
  } else {
    std::random_device device;
    for (unsigned char& v : b) v = static_cast<unsigned char>(device());
  }
  b[6] = static_cast<unsigned char>((b[6] & 0x0f) | 0x40);  // version 4
  b[8] = static_cast<unsigned char>((b[8] & 0x3f) | 0x80);  // variant 1
  char text[37];
  std::snprintf(text, sizeof text,
                "%02x%02x%02x%02x-%02x%02x-%02x%02x-%02x%02x-%02x%02x%02x%02x%02x%02x", b[0], b[1],
                b[2], b[3], b[4], b[5], b[6], b[7], b[8], b[9], b[10], b[11], b[12], b[13], b[14],
                b[15]);
  return text;
}

TrackedFrames::TrackedFrames(TrackedSettings settings) : settings_(std::move(settings)) {}

std::vector<TrackerWrapperPacket> TrackedFrames::on_state(const sim_state_t& state) {
  std::vector<TrackerWrapperPacket> due;
  if (!sim_state_numbers_fit(state)) {
    ++refused_;
    return due;
  }
  if (state.sim_time < previous_time_) {  // physics was reset
    waiting_.clear();
    kick_.reset();
    next_sample_ = 0;
  }
  detect_kick(state);
  previous_time_ = state.sim_time;
  if (state.sim_time + 1e-9 >= next_sample_) {
    next_sample_ = state.sim_time + 1.0 / settings_.rate;
    if (waiting_.size() >= kMaxWaiting) waiting_.pop_front();
    waiting_.push_back(state);
  }
  while (!waiting_.empty() && waiting_.front().sim_time + latency_ <= state.sim_time + 1e-9) {
    due.push_back(build(waiting_.front()));
    waiting_.pop_front();
  }
  return due;
}

void TrackedFrames::detect_kick(const sim_state_t& state) {
  const double* v = state.ball.linear_velocity;
  const double speed = std::hypot(v[0], v[1]);
  if (previous_time_ >= 0 && state.ball_present && speed - previous_ball_speed_ > kKickSpeedJump) {
    const double* p = state.ball.position;
    const robot_state_t* kicker = nullptr;
    double nearest = kKickerReach;
    for (const robot_state_t& robot : state.robots) {
      const double d = std::hypot(robot.x - p[0], robot.y - p[1]);
      if (d < nearest) {
        nearest = d;
        kicker = &robot;
      }
    }
    if (kicker != nullptr) {
      KickedBall kick;
      set(*kick.mutable_pos(), p[0], p[1]);
      set(*kick.mutable_vel(), v);
      kick.set_start_timestamp(state.sim_time);
      RobotId* id = kick.mutable_robot_id();
      id->set_id(static_cast<uint32_t>(kicker->robot_id));
      id->set_team(kicker->team == team_t::YELLOW ? YELLOW : BLUE);
      if (settings_.ball_model && speed > 0) {
        // Two phases: sliding to k_switch of the speed, then rolling to rest.
        const BallModel& m = *settings_.ball_model;
        const double v_switch = m.slide_to_roll_ratio * speed;
        const double t_slide = (speed - v_switch) / m.sliding_deceleration;
        const double t_roll = v_switch / m.rolling_deceleration;
        const double distance = (speed + v_switch) / 2 * t_slide + v_switch / 2 * t_roll;
        kick.set_stop_timestamp(state.sim_time + t_slide + t_roll);
        set(*kick.mutable_stop_pos(), p[0] + v[0] / speed * distance,
            p[1] + v[1] / speed * distance);
      }
      kick_ = kick;
    }
  } else if (kick_ && speed < kStoppedSpeed) {
    kick_.reset();  // the kicked ball has stopped
  }
  previous_ball_speed_ = speed;
}

TrackerWrapperPacket TrackedFrames::build(const sim_state_t& state) {
  TrackerWrapperPacket packet;
  packet.set_uuid(settings_.uuid);
  packet.set_source_name("ubersim");
  TrackedFrame* frame = packet.mutable_tracked_frame();
  frame->set_frame_number(frame_number_++);
  frame->set_timestamp(state.sim_time);
  if (state.ball_present) {
    TrackedBall* ball = frame->add_balls();
    set(*ball->mutable_pos(), state.ball.position);
    set(*ball->mutable_vel(), state.ball.linear_velocity);
    ball->set_visibility(1);
  }
  for (const robot_state_t& r : state.robots) {
    TrackedRobot* robot = frame->add_robots();
    robot->mutable_robot_id()->set_id(static_cast<uint32_t>(r.robot_id));
    robot->mutable_robot_id()->set_team(r.team == team_t::YELLOW ? YELLOW : BLUE);
    set(*robot->mutable_pos(), r.x, r.y);
    robot->set_orientation(static_cast<float>(r.orientation));
    set(*robot->mutable_vel(), r.vx, r.vy);
    robot->set_vel_angular(static_cast<float>(r.omega));
    robot->set_visibility(1);
  }
  if (kick_ && kick_->start_timestamp() <= state.sim_time) *frame->mutable_kicked_ball() = *kick_;
  // What ground truth really gives: the ball's height, and kicks. One ball only.
  frame->add_capabilities(CAPABILITY_DETECT_FLYING_BALLS);
  frame->add_capabilities(CAPABILITY_DETECT_KICKED_BALLS);
  return packet;
}

}  // namespace ubersim::ssl
