#include "ubersim/vision/vision_shell.hpp"

#include <chrono>
#include <limits>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/vision_schedule_t.hpp>

#include "ubersim/field_config.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/process_host.hpp"
#include "ubersim/robot_type_definition.hpp"
#include "ubersim/sim_control_requests.hpp"
#include "ubersim/spdlog.hpp"
#include "ubersim/topics.hpp"
#include "ubersim/vision/vision_emulator.hpp"
#include "ubersim/vision_backpressure.hpp"

namespace ubersim::vision {
namespace {

using Clock = ProcessHost::Clock;

// The last schedule again, this long after anything was said on
// SIM_VISION_SCHEDULE, for a process that started later.
constexpr auto kScheduleRepeat = std::chrono::milliseconds(100);
// The longest wait of the loop (the schedule repeat and the demand's
// once-a-second check ride on its wakeups).
constexpr auto kMaxWait = std::chrono::milliseconds(100);
// On SIGTERM, at most this long for what already waits in the socket.
constexpr auto kDrainLimit = std::chrono::seconds(1);

void log_start(const VisionProfile& profile, const ChannelNames& channels) {
  spdlog::info("profile '{}', seed {}, {} camera(s), latency {} s (jitter {} s), processing {} s",
               profile.name, profile.seed, profile.cameras.size(), profile.latency,
               profile.latency_jitter, profile.processing_time);
  for (const CameraProfile& c : profile.cameras) {
    spdlog::info("camera {}: {} Hz, phase {} s, at ({}, {}, {}) m, f {} px, {}x{} px", c.id,
                 c.frame_rate, c.phase, c.position.x(), c.position.y(), c.position.z(),
                 c.focal_length, c.image_width, c.image_height);
  }
  spdlog::info(
      "subscribing {} and {}; publishing {} and {}", channel_name(channels, topics::kSimState),
      channel_name(channels, topics::kSimGeometry), channel_name(channels, topics::kVision),
      channel_name(channels, topics::kVisionGeometry));
}

void log_summary(const VisionStats& s, std::uint64_t undecodable) {
  // Frames lost first: a loss must not hide in the middle of the line.
  spdlog::log(s.capture_instants_missed > 0 ? spdlog::level::warn : spdlog::level::info,
              "summary: frames lost {}; frames published {}, captured {}, dropped at reset {}; sim "
              "states used {}, invalid {}, out of order {}, repeated {}, undecodable {}; resets "
              "{}; invalid geometry {}; camera sets applied {}, camera sets invalid {}, frames "
              "dropped with a camera {}",
              s.capture_instants_missed, s.frames_published, s.frames_captured,
              s.frames_dropped_at_reset, s.states_used, s.states_invalid, s.states_out_of_order,
              s.states_repeated, undecodable, s.resets, s.geometry_invalid, s.camera_sets_applied,
              s.camera_sets_invalid, s.frames_dropped_with_camera);
}

void log_realism(const emulator_realism_t& realism, const VisionProfile& p) {
  spdlog::info(
      "realism from '{}': robot sigma {} m / {} rad, ball sigma {} m, detection {} / {}, "
      "false balls {}/s, latency {} s, camera overlap {} m, position error {} m, object "
      "offset {} m, ball area sigma {}",
      realism.sender, p.robot_sigma_x, p.robot_sigma_orientation, p.ball_sigma_x,
      p.robot_detection_probability, p.ball_detection_probability, p.false_ball_rate,
      realism.vision_latency, p.camera_overlap, p.camera_position_error, p.object_position_offset,
      p.ball_area_sigma);
}

void log_cameras(const vision_cameras_t& cameras, const VisionEmulator& emulator) {
  spdlog::info("cameras from '{}': {} camera(s), overlap {} m", cameras.sender,
               emulator.camera_count(), emulator.profile().camera_overlap);
  for (std::size_t i = 0; i < emulator.camera_count(); ++i) {
    const PinholeCamera& c = emulator.camera(i).truth();
    spdlog::info("camera {}: at ({}, {}, {}) m, f {} px", emulator.camera(i).id(), c.position().x(),
                 c.position().y(), c.position().z(), c.intrinsics().focal_length);
  }
}

// "Listening, no state yet" (step -1): what physics in sync mode waits for
// before its first state.
vision_schedule_t listening_schedule() {
  vision_schedule_t schedule{};
  schedule.t_state = -1;
  schedule.step = -1;
  schedule.next_publication = schedule.next_capture = std::numeric_limits<double>::infinity();
  return schedule;
}

void list_frames(vision_schedule_t& schedule, const std::vector<vision_frame_t>& frames) {
  schedule.num_frames = static_cast<std::int32_t>(frames.size());
  schedule.camera_id.clear();
  schedule.frame_number.clear();
  schedule.t_capture.clear();
  for (const vision_frame_t& frame : frames) {
    schedule.camera_id.push_back(frame.camera_id);
    schedule.frame_number.push_back(frame.frame_number);
    schedule.t_capture.push_back(frame.t_capture);
  }
}

// Everything around the core that is not the host's: what each message does,
// the schedule and its acknowledgements, when the truth demand is renewed, the
// geometry. One method per input or repeat; run_vision_process below hands
// them to the host.
class VisionShell {
 public:
  VisionShell(ProcessHost& host, VisionEmulator& emulator)
      : host_(host),
        emulator_(emulator),
        vision_(host.bus(), host.channels(), topics::kVision),
        vision_geometry_(host.bus(), host.channels(), topics::kVisionGeometry),
        schedule_out_(host.bus(), host.channels(), topics::kVisionSchedule) {}

  // The host's timers of the two repeats: a schedule or a geometry said out
  // of turn puts its repeat off by a whole period.
  void repeat_on(ProcessHost::Timer& schedule, ProcessHost::Timer& geometry) {
    schedule_repeat_ = &schedule;
    geometry_repeat_ = &geometry;
  }

  void on_sim_state(const sim_state_t& state);
  void on_sim_geometry(const field_geometry_t& geometry);
  void on_sim_control(const sim_control_t& request);
  void on_realism(const emulator_realism_t& realism);
  void on_cameras(const vision_cameras_t& cameras);

  // Ask physics for the field now rather than wait for its next periodic one.
  void request_geometry();
  void repeat_geometry(Clock::time_point now) { publish_geometry(now); }
  void repeat_schedule(Clock::time_point now);
  // The truth demand as it stands: what the host sends (ProcessHost::ask_for_truth).
  truth_demand_t truth_demand();
  // SIGTERM: what waits is still handled, then the summary.
  void stop();

 private:
  void warn_lost_frames(std::uint64_t lost_before, double sim_time);
  void publish_geometry(Clock::time_point now);
  void after_state(const sim_state_t& state, const std::vector<vision_frame_t>& frames, bool always,
                   Clock::time_point now);
  void announce_demand(bool always, double sim_time, Clock::time_point now);
  void renew_demand();
  void send_schedule(Clock::time_point now);

  ProcessHost& host_;
  VisionEmulator& emulator_;
  // Channels resolved once: frames and schedules go out up to thousands of
  // times a second as fast as possible.
  Publisher<vision_frame_t> vision_;
  Publisher<vision_geometry_t> vision_geometry_;
  Publisher<vision_schedule_t> schedule_out_;
  ProcessHost::Timer* schedule_repeat_ = nullptr;
  ProcessHost::Timer* geometry_repeat_ = nullptr;
  ThrottledLog bad_content_;
  ThrottledLog lost_frames_;
  vision_schedule_t schedule_ = listening_schedule();
  double announced_next_ = -1;
  // What ground truth it needs is said again only when the frames it
  // announced run low (every kFramesAhead - 2 frames of a camera), after a
  // reset or a realism change, and once a second. Each demand wakes physics,
  // and one per frame was a third of what physics woke for in real time
  // (docs/sync.md).
  double demand_renewal_ = 0;  // sim time
  truth_demand_t demand_{};
  bool demand_made_ = false;
};

void VisionShell::on_sim_state(const sim_state_t& state) {
  const std::uint64_t lost_before = emulator_.stats().capture_instants_missed;
  auto outcome = emulator_.on_sim_state(state);
  warn_lost_frames(lost_before, state.sim_time);
  using Verdict = VisionEmulator::Verdict;
  switch (outcome.verdict) {
    case Verdict::Invalid:
      bad_content_.warn("invalid", "skipped a SIM_STATE: " + outcome.problem);
      break;
    case Verdict::OutOfOrder:
      bad_content_.warn("out_of_order", "skipped a SIM_STATE older than one already used");
      break;
    case Verdict::Reset:
      spdlog::info("sim time went back to {} s: simulation reset, pending frames dropped",
                   state.sim_time);
      after_state(state, outcome.frames, true, host_.now());
      break;
    case Verdict::Repeated:
      break;
    case Verdict::Used:
      after_state(state, outcome.frames, false, host_.now());
      break;
  }
  for (const vision_frame_t& frame : outcome.frames) vision_(frame);
}

void VisionShell::warn_lost_frames(std::uint64_t lost_before, double sim_time) {
  const std::uint64_t lost = emulator_.stats().capture_instants_missed;
  if (lost == lost_before) return;
  lost_frames_.warn("lost", fmt::format("lost {} frame(s) before sim time {} s ({} so far): "
                                        "no SIM_STATE reached this process for their "
                                        "capture instants (it fell behind physics, or "
                                        "the datagrams were dropped)",
                                        lost - lost_before, sim_time, lost));
}

// The schedule goes out before the frames it lists, on the same bus, so a
// listener (the radio emulator in sync mode) knows when a frame was published
// before any answer to it can reach it.
void VisionShell::after_state(const sim_state_t& state, const std::vector<vision_frame_t>& frames,
                              bool always, Clock::time_point now) {
  // The demand before the schedule (physics in sync mode starts on the
  // schedule, and must know the demand by then).
  announce_demand(always, state.sim_time, now);
  const double next = emulator_.next_publication();
  // As fast as possible (and in sync mode) physics waits for this process
  // to acknowledge a state at most kVisionLead behind it: every
  // kVisionAckInterval of sim time at least, the schedule goes out even
  // when it has nothing new (docs/vision.md, "As fast as possible").
  const bool acknowledge =
      state.speed_factor == 0 &&
      state.sim_time >= schedule_.t_state + kVisionAckInterval - CaptureSchedule::kTolerance;
  if (!always && frames.empty() && next == announced_next_ && !acknowledge) return;
  announced_next_ = next;
  schedule_.t_state = state.sim_time;
  schedule_.step = state.step;
  schedule_.next_publication = next;
  schedule_.next_capture = emulator_.next_capture();
  list_frames(schedule_, frames);
  // Only sync mode (speed 0 in the state) waits for frames; in real time
  // the schedule's one reader is physics, which wants to know that vision
  // listens: the repetition says so 10 times a second.
  if (!always && state.speed_factor > 0) return;
  send_schedule(now);
}

// A new demand, sent at once, when the last one runs low or `always`;
// otherwise the host repeats the one it has once a second.
void VisionShell::announce_demand(bool always, double sim_time, Clock::time_point now) {
  if (!always && sim_time < demand_renewal_ - CaptureSchedule::kTolerance) return;
  renew_demand();
  host_.send_truth_demand(now);
}

void VisionShell::renew_demand() {
  demand_renewal_ = emulator_.demand_renewal_time();
  demand_ = emulator_.truth_demand();
  demand_made_ = true;
}

truth_demand_t VisionShell::truth_demand() {
  if (!demand_made_) renew_demand();  // the first, before the first state
  return demand_;
}

void VisionShell::send_schedule(Clock::time_point now) {
  schedule_out_(schedule_);
  schedule_repeat_->due_at(now + kScheduleRepeat);
}

void VisionShell::repeat_schedule(Clock::time_point now) {
  // The frames were announced once: a repetition must not announce them again.
  list_frames(schedule_, {});
  // Not forced: in real time this repetition runs 10 times a second, and
  // the demand's own rules (renewal, once a second; at once before the
  // first state) already put one out before any schedule physics waits for.
  announce_demand(false, emulator_.sim_time(), now);
  send_schedule(now);
}

void VisionShell::publish_geometry(Clock::time_point now) {
  if (!emulator_.field()) return;  // nothing to say about the field yet
  vision_geometry_(emulator_.geometry_message());
  geometry_repeat_->due_at(now + geometry_repeat_->period());
}

void VisionShell::on_sim_geometry(const field_geometry_t& geometry) {
  const auto before = emulator_.stats().geometry_invalid;
  if (emulator_.on_field_geometry(geometry)) {
    spdlog::info("field '{}' ({} x {} m), ball radius {} m", geometry.name, geometry.field_length,
                 geometry.field_width, geometry.ball_radius);
    publish_geometry(host_.now());
  } else if (emulator_.stats().geometry_invalid != before) {
    bad_content_.warn("geometry", "ignored an invalid SIM_GEOMETRY");
  }
}

// Robot types defined at run time (e.g. SSL robot specs): the same text
// physics builds the robots from gives their size here.
void VisionShell::on_sim_control(const sim_control_t& request) {
  if (request.action != sim_control_t::DEFINE_ROBOT_TYPE) return;
  try {
    const RobotTypeConfig type =
        parse_robot_type_definition(request.robot_type_name, request.robot_type_config);
    if (!emulator_.define_robot_size(type.name,
                                     RobotSize{type.radius, type.height, type.front_distance})) {
      bad_content_.warn("robot_types", "too many robot types defined; ignored " + type.name);
      return;
    }
    spdlog::info("robot type {} defined: radius {} m, height {} m", type.name, type.radius,
                 type.height);
  } catch (const std::exception& error) {
    bad_content_.warn("robot_type",
                      std::string("ignored a robot type definition: ") + error.what());
  }
}

// Realism changed at run time (e.g. an SSL realism preset through the bridge).
void VisionShell::on_realism(const emulator_realism_t& realism) {
  const std::string problem = emulator_.apply_realism(realism);
  if (!problem.empty()) {
    bad_content_.warn("realism",
                      "ignored a realism change from '" + realism.sender + "': " + problem);
    return;
  }
  demand_renewal_ = 0;  // the latency changed: so did the frames' publication times
  log_realism(realism, emulator_.profile());
}

// New cameras at run time (e.g. the calibrations of an SSL client's geometry).
void VisionShell::on_cameras(const vision_cameras_t& cameras) {
  const std::string problem = emulator_.apply_cameras(cameras);
  if (!problem.empty()) {
    bad_content_.warn("cameras", "ignored a camera set from '" + cameras.sender + "': " + problem);
    return;
  }
  demand_renewal_ = 0;  // other capture instants: other states needed
  log_cameras(cameras, emulator_);
  publish_geometry(host_.now());  // the new calibrations, at once
}

void VisionShell::request_geometry() {
  publish(host_.bus(), host_.channels(), topics::kSimControl,
          geometry_request("ubersim_vision", 1));
}

// What already waits in the socket (physics may have sent its last states
// just before it exited) is still handled, so that a run's last frames are
// published rather than lost. Bounded: as fast as possible physics is at most
// kVisionLead ahead; a flood must not hold the exit.
void VisionShell::stop() {
  const auto deadline = host_.now() + kDrainLimit;
  while (host_.now() < deadline && host_.bus().handle_pending() > 0) {
  }
  log_summary(emulator_.stats(), host_.bus().malformed_count());
}

VisionEmulator make_emulator(const VisionProfile& profile, const VisionProcessOptions& options) {
  const std::string config_dir = options.common.config_root();
  VisionEmulator emulator(profile, RobotSizes::from_config_dir(config_dir));
  if (!options.field.empty()) {
    emulator.on_field_geometry(
        load_field_config(config_dir, options.field).to_message(profile.ball_radius));
  }
  return emulator;
}

}  // namespace

int run_vision_process(const VisionProcessOptions& options) {
  const ChannelNames channels = options.common.channels();
  VisionProfile profile = load_vision_profile(options.common.config_root(), options.profile);
  if (options.seed) profile.seed = *options.seed;
  log_start(profile, channels);
  VisionEmulator emulator = make_emulator(profile, options);

  ProcessHost host(with_receive_buffer(options.common.lcm_url), channels, "vision");
  VisionShell shell(host, emulator);
  MessageBus& bus = host.bus();
  subscribe(bus, channels, topics::kSimState, [&](const sim_state_t& m) { shell.on_sim_state(m); });
  subscribe(bus, channels, topics::kSimGeometry,
            [&](const field_geometry_t& m) { shell.on_sim_geometry(m); });
  subscribe(bus, channels, topics::kSimControl,
            [&](const sim_control_t& m) { shell.on_sim_control(m); });
  subscribe(bus, channels, topics::kEmulatorRealism,
            [&](const emulator_realism_t& m) { shell.on_realism(m); });
  subscribe(bus, channels, topics::kVisionCameras,
            [&](const vision_cameras_t& m) { shell.on_cameras(m); });

  // The demand goes out when the shell renews it (and once a second).
  host.ask_for_truth([&] { return shell.truth_demand(); });
  ProcessHost::Timer& schedule_repeat =
      host.every(kScheduleRepeat, [&](Clock::time_point now) { shell.repeat_schedule(now); });
  const auto geometry_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(profile.geometry_period));
  ProcessHost::Timer& geometry_repeat =
      host.every(geometry_period, [&](Clock::time_point now) { shell.repeat_geometry(now); });
  shell.repeat_on(schedule_repeat, geometry_repeat);
  host.at_stop([&] { shell.stop(); });

  // At start: ask for the field, say the one known (--field), then the
  // demand and the schedule that says "listening" (physics in sync mode waits
  // for it before its first state). Said here, before the first wait, the
  // demand also counts as the announcer's first.
  shell.request_geometry();
  shell.repeat_geometry(host.now());
  shell.repeat_schedule(host.now());
  return host.run(kMaxWait);
}

}  // namespace ubersim::vision
