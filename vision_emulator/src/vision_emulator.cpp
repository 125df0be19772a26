#include "ubersim/vision/vision_emulator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "ubersim/spdlog.hpp"
#include "ubersim/vision/sim_state_check.hpp"

namespace ubersim::vision {
namespace {

// Whether `duration` is a whole number of steps of `dt` (to a microsecond).
bool whole_steps(double duration, double dt) {
  const double steps = duration / dt;
  return std::abs(steps - std::round(steps)) * dt <= CaptureSchedule::kTolerance;
}

std::vector<char> encoded(const field_geometry_t& geometry) {
  std::vector<char> bytes(static_cast<std::size_t>(geometry.getEncodedSize()));
  geometry.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

}  // namespace

VisionEmulator::VisionEmulator(VisionProfile profile, RobotSizes robot_sizes)
    : profile_(std::move(profile)),
      robot_sizes_(std::move(robot_sizes)),
      ball_radius_(profile_.ball_radius) {
  cameras_.reserve(profile_.cameras.size());
  for (const CameraProfile& c : profile_.cameras) cameras_.push_back(make_camera(c));
  update_regions();
}

VisionEmulator::Camera VisionEmulator::make_camera(const CameraProfile& c) const {
  Camera camera{CameraDetector(c, profile_, profile_.seed),
                CaptureSchedule(c.frame_rate, c.phase),
                RandomSource(profile_.seed, 2 * static_cast<std::uint64_t>(c.id) + 1),
                std::deque<double>{},
                DelayLine<vision_frame_t>{},
                c};
  while (camera.upcoming_jitter.size() < kFramesAhead) {
    camera.upcoming_jitter.push_back(camera.latency_random.gaussian());
  }
  return camera;
}

void VisionEmulator::update_regions() {
  std::vector<Eigen::Vector2d> centres;
  for (const Camera& camera : cameras_) {
    centres.push_back(camera.detector.truth().position().head<2>());
  }
  const CameraRegions regions(std::move(centres), profile_.camera_overlap);
  for (std::size_t i = 0; i < cameras_.size(); ++i) cameras_[i].detector.set_region(regions, i);
}

bool VisionEmulator::on_field_geometry(const field_geometry_t& geometry) {
  if (!find_field_geometry_problem(geometry).empty()) {
    ++stats_.geometry_invalid;
    return false;
  }
  const bool changed = !field_ || encoded(*field_) != encoded(geometry);
  field_ = geometry;
  ball_radius_ = geometry.ball_radius;
  return changed;
}

vision_geometry_t VisionEmulator::geometry_message() const {
  vision_geometry_t message{};
  message.t_sent = clock_.now();
  if (field_) message.field = *field_;
  message.num_cameras = static_cast<std::int32_t>(cameras_.size());
  for (const Camera& camera : cameras_) {
    message.cameras.push_back(camera.detector.reported_calibration());
  }
  return message;
}

const WorldSnapshot& VisionEmulator::snapshot(const sim_state_t& state) {
  world_.sim_time = state.sim_time;
  world_.ball_present = state.ball_present;
  world_.ball =
      Eigen::Vector3d(state.ball.position[0], state.ball.position[1], state.ball.position[2]);
  world_.ball_radius = ball_radius_;
  world_.robots.clear();
  world_.footprints.clear();
  for (const robot_state_t& r : state.robots) {
    WorldSnapshot::Robot robot;
    robot.team = r.team;
    robot.id = r.robot_id;
    robot.position = Eigen::Vector2d(r.x, r.y);
    robot.orientation = r.orientation;
    robot.size = robot_sizes_.get(r.robot_type);
    world_.robots.push_back(robot);
    RobotFootprint footprint;
    footprint.center = robot.position;
    footprint.forward = Eigen::Vector2d(std::cos(r.orientation), std::sin(r.orientation));
    footprint.radius = robot.size.radius;
    footprint.height = robot.size.height;
    footprint.front_distance = robot.size.front_distance;
    world_.footprints.push_back(footprint);
  }
  return world_;
}

double VisionEmulator::latency_of(const Camera& camera, std::size_t ahead) {
  // Jitter never makes a frame leave before it was processed.
  return std::max(
      camera.timing.processing_time,
      camera.timing.latency + camera.timing.latency_jitter * camera.upcoming_jitter.at(ahead));
}

double VisionEmulator::release_time(Camera& camera, double t_capture) {
  const double latency = latency_of(camera);
  camera.upcoming_jitter.pop_front();
  camera.upcoming_jitter.push_back(camera.latency_random.gaussian());
  return t_capture + latency;
}

double VisionEmulator::next_capture() const {
  double next = std::numeric_limits<double>::infinity();
  for (const Camera& camera : cameras_) {
    if (camera.schedule.started()) next = std::min(next, camera.schedule.next_instant());
  }
  return next;
}

truth_demand_t VisionEmulator::truth_demand() const {
  truth_demand_t demand{};
  demand.consumer = "vision";
  for (const Camera& camera : cameras_) {
    demand.period.push_back(1.0 / camera.timing.frame_rate);
    demand.phase.push_back(camera.timing.phase);
    for (double t : camera.pending.release_times()) demand.instants.push_back(t);
    // Before the first state the first capture is at the phase (a run starts at 0).
    const std::int64_t next = camera.schedule.started() ? camera.schedule.next_index() : 0;
    for (std::size_t ahead = 0; ahead < kFramesAhead; ++ahead) {
      demand.instants.push_back(camera.schedule.instant(next + static_cast<std::int64_t>(ahead)) +
                                latency_of(camera, ahead));
    }
  }
  demand.num_periodic = static_cast<std::int32_t>(demand.period.size());
  demand.num_instants = static_cast<std::int32_t>(demand.instants.size());
  return demand;
}

double VisionEmulator::demand_renewal_time() const {
  double renewal = std::numeric_limits<double>::infinity();
  for (const Camera& camera : cameras_) {
    if (!camera.schedule.started()) return 0;
    // Once this capture is done, one announced frame is left ahead.
    renewal =
        std::min(renewal, camera.schedule.instant(camera.schedule.next_index() +
                                                  static_cast<std::int64_t>(kFramesAhead) - 2));
  }
  return renewal;
}

double VisionEmulator::next_publication() const {
  double next = std::numeric_limits<double>::infinity();
  for (const Camera& camera : cameras_) {
    if (!camera.pending.empty()) next = std::min(next, camera.pending.front_release());
    if (camera.schedule.started()) {
      next = std::min(next, camera.schedule.next_instant() + latency_of(camera));
    }
  }
  return next;
}

void VisionEmulator::restart_after_reset() {
  ++stats_.resets;
  for (Camera& camera : cameras_) {
    // Frames of the world before the reset would show robots where they no longer are.
    stats_.frames_dropped_at_reset += camera.pending.size();
    camera.pending.clear();
    camera.schedule.restart();
  }
}

void VisionEmulator::check_step_fits(const sim_state_t& state) {
  if (step_checked_) return;
  step_checked_ = true;
  for (const Camera& camera : cameras_) {
    const CameraProfile& c = camera.timing;
    if (!whole_steps(c.period(), state.dt) || !whole_steps(c.phase, state.dt)) {
      spdlog::warn(
          "camera {}: its capture instants ({} Hz, phase {} s) fall between simulation steps of "
          "{} s; each is served by the first step after it (up to one step late)",
          c.id, c.frame_rate, c.phase, state.dt);
    }
  }
}

// Missed instants skip numbers, as they do for a camera counting alone.
void VisionEmulator::share_frame_number(std::vector<DueCapture>& due) {
  if (due.empty()) return;
  std::int64_t missed = 0;
  for (const DueCapture& item : due) missed = std::max(missed, item.capture.missed_instants);
  const std::int64_t number = next_shared_frame_number_ + missed;
  for (DueCapture& item : due) item.capture.frame_number = number;
  next_shared_frame_number_ = number + 1;
}

VisionEmulator::Output VisionEmulator::on_sim_state(const sim_state_t& state) {
  Output outcome;
  outcome.problem = find_sim_state_problem(state);
  if (!outcome.problem.empty()) {
    ++stats_.states_invalid;
    outcome.verdict = Verdict::Invalid;
    return outcome;
  }
  if (clock_.started() && state.step == clock_.step() && state.sim_time == clock_.now()) {
    ++stats_.states_repeated;  // physics repeats its state while paused
    outcome.verdict = Verdict::Repeated;
    return outcome;
  }
  switch (clock_.update(state.sim_time, state.step)) {
    case SimClock::Update::Rejected:
      ++stats_.states_out_of_order;
      outcome.verdict = Verdict::OutOfOrder;
      return outcome;
    case SimClock::Update::Reset:
      restart_after_reset();
      outcome.verdict = Verdict::Reset;
      break;
    case SimClock::Update::Advanced:
      break;
  }
  ++stats_.states_used;
  check_step_fits(state);

  std::vector<DueCapture> due;
  for (Camera& camera : cameras_) {
    if (const auto capture = camera.schedule.on_state(state.sim_time)) {
      due.push_back(DueCapture{&camera, *capture});
    }
  }
  if (!due.empty()) snapshot(state);
  if (profile_.shared_frame_numbers) share_frame_number(due);
  for (const DueCapture& item : due) {
    Camera& camera = *item.camera;
    stats_.capture_instants_missed += static_cast<std::uint64_t>(item.capture.missed_instants);
    ++stats_.frames_captured;
    camera.pending.push(release_time(camera, state.sim_time),
                        camera.detector.capture(world_, item.capture.frame_number));
  }

  // Everything due is published at this step, camera by camera in id order
  // (within one step, sim time cannot order them any finer).
  for (Camera& camera : cameras_) {
    // "Reaches" to a microsecond, so a latency of whole steps is never a step late by rounding.
    for (auto& item : camera.pending.pop_due(state.sim_time + CaptureSchedule::kTolerance)) {
      outcome.frames.push_back(std::move(item.second));
    }
  }
  stats_.frames_published += outcome.frames.size();
  return outcome;
}

}  // namespace ubersim::vision
