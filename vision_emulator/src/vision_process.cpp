#include "ubersim/vision/vision_process.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <functional>
#include <limits>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/vision_schedule_t.hpp>

#include "ubersim/cli.hpp"
#include "ubersim/field_config.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/robot_type_definition.hpp"
#include "ubersim/shutdown.hpp"
#include "ubersim/vision/vision_emulator.hpp"
#include "ubersim/vision_backpressure.hpp"

namespace ubersim::vision {
namespace {

using Clock = std::chrono::steady_clock;

void log_start(const VisionProfile& profile, const VisionProcessOptions& options) {
  spdlog::info("profile '{}', seed {}, {} camera(s), latency {} s (jitter {} s), processing {} s",
               profile.name, profile.seed, profile.cameras.size(), profile.latency,
               profile.latency_jitter, profile.processing_time);
  for (const CameraProfile& c : profile.cameras) {
    spdlog::info("camera {}: {} Hz, phase {} s, at ({}, {}, {}) m, f {} px, {}x{} px", c.id,
                 c.frame_rate, c.phase, c.position.x(), c.position.y(), c.position.z(),
                 c.focal_length, c.image_width, c.image_height);
  }
  spdlog::info("subscribing {} and {}; publishing {} and {}", options.channels(Channel::SimState),
               options.channels(Channel::SimGeometry), options.channels(Channel::Vision),
               options.channels(Channel::VisionGeometry));
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

// On SIGTERM, what already waits in the socket (physics may have sent its
// last states just before it exited) is still handled, so that a run's last
// frames are published rather than lost. Bounded: as fast as possible physics
// is at most kVisionLead ahead; a flood must not hold the exit.
void handle_what_waits(MessageBus& bus) {
  const auto deadline = Clock::now() + std::chrono::seconds(1);
  while (Clock::now() < deadline && bus.handle_pending() > 0) {
  }
}

}  // namespace

int run_vision_process(const VisionProcessOptions& options, const ShutdownSignal& shutdown) {
  VisionProfile profile = load_vision_profile(options.config_dir, options.profile);
  if (options.seed) profile.seed = *options.seed;
  log_start(profile, options);
  const auto geometry_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(profile.geometry_period));

  VisionEmulator emulator(profile, RobotSizes::from_config_dir(options.config_dir));
  if (!options.field.empty()) {
    emulator.on_field_geometry(
        load_field_config(options.config_dir, options.field).to_message(profile.ball_radius));
  }

  MessageBus bus(with_receive_buffer(options.lcm_url));
  ThrottledLog bad_content;
  ThrottledLog lost_frames;
  const std::string vision_channel = options.channels(Channel::Vision);
  const std::string geometry_channel = options.channels(Channel::VisionGeometry);
  Clock::time_point next_geometry = Clock::now();
  auto publish_geometry = [&] {
    if (!emulator.field()) return;  // nothing to say about the field yet
    bus.publish(geometry_channel, emulator.geometry_message());
    next_geometry = Clock::now() + geometry_period;
  };

  // The schedule goes out before the frames it lists, on the same bus, so a
  // listener (the radio emulator in sync mode) knows when a frame was
  // published before any answer to it can reach it.
  const std::string schedule_channel = options.channels.extra(kVisionScheduleChannel);
  const std::string demand_channel = options.channels.extra(kTruthDemandChannel);
  vision_schedule_t schedule{};
  // Until the first state: "listening, no state yet" (step -1), which is what
  // physics in sync mode waits for before its first state.
  schedule.t_state = -1;
  schedule.step = -1;
  schedule.next_publication = schedule.next_capture = std::numeric_limits<double>::infinity();
  double announced_next = -1;
  Clock::time_point last_schedule{};
  // What ground truth it needs: said again only when the frames it announced
  // run low (every kFramesAhead - 2 frames of a camera), after a reset or a
  // realism change, and once a second. Each demand wakes physics, and one per
  // frame was a third of what physics woke for in real time (docs/sync.md).
  double demand_renewal = 0;  // sim time
  Clock::time_point last_demand{};
  auto announce_demand = [&](bool now, double sim_time) {
    if (!now && sim_time < demand_renewal - CaptureSchedule::kTolerance &&
        Clock::now() - last_demand < std::chrono::seconds(1)) {
      return;
    }
    bus.publish(demand_channel, emulator.truth_demand());
    demand_renewal = emulator.demand_renewal_time();
    last_demand = Clock::now();
  };
  auto publish_schedule = [&](const sim_state_t& state, const std::vector<vision_frame_t>& frames,
                              bool always) {
    // The demand before the schedule (physics in sync mode starts on the
    // schedule, and must know the demand by then).
    announce_demand(always, state.sim_time);
    const double next = emulator.next_publication();
    // As fast as possible (and in sync mode) physics waits for this process
    // to acknowledge a state at most kVisionLead behind it: every
    // kVisionAckInterval of sim time at least, the schedule goes out even
    // when it has nothing new (docs/vision.md, "As fast as possible").
    const bool acknowledge =
        state.speed_factor == 0 &&
        state.sim_time >= schedule.t_state + kVisionAckInterval - CaptureSchedule::kTolerance;
    if (!always && frames.empty() && next == announced_next && !acknowledge) return;
    announced_next = next;
    schedule.t_state = state.sim_time;
    schedule.step = state.step;
    schedule.next_publication = next;
    schedule.next_capture = emulator.next_capture();
    schedule.num_frames = static_cast<std::int32_t>(frames.size());
    schedule.camera_id.clear();
    schedule.frame_number.clear();
    schedule.t_capture.clear();
    for (const vision_frame_t& frame : frames) {
      schedule.camera_id.push_back(frame.camera_id);
      schedule.frame_number.push_back(frame.frame_number);
      schedule.t_capture.push_back(frame.t_capture);
    }
    // Only sync mode (speed 0 in the state) waits for frames; in real time
    // the schedule's one reader is physics, which wants to know that vision
    // listens: the repetition below says so 10 times a second.
    if (!always && state.speed_factor > 0) return;
    bus.publish(schedule_channel, schedule);
    last_schedule = Clock::now();
  };
  // The last schedule again, 10 times a second when nothing new was said, for
  // a process that started later.
  const auto repeat_schedule = [&] {
    if (Clock::now() - last_schedule < std::chrono::milliseconds(100)) return;
    // The frames were announced once: a repetition must not announce them again.
    schedule.num_frames = 0;
    schedule.camera_id.clear();
    schedule.frame_number.clear();
    schedule.t_capture.clear();
    // Not forced: in real time this repetition runs 10 times a second, and
    // the demand's own rules (renewal, once a second; at once before the
    // first state) already put one out before any schedule physics waits for.
    announce_demand(false, emulator.sim_time());
    bus.publish(schedule_channel, schedule);
    last_schedule = Clock::now();
  };

  bus.subscribe<sim_state_t>(
      options.channels(Channel::SimState),
      std::function<void(const sim_state_t&)>([&](const sim_state_t& state) {
        const std::uint64_t lost_before = emulator.stats().capture_instants_missed;
        auto outcome = emulator.on_sim_state(state);
        if (const std::uint64_t lost = emulator.stats().capture_instants_missed;
            lost > lost_before) {
          lost_frames.warn("lost", fmt::format("lost {} frame(s) before sim time {} s ({} so far): "
                                               "no SIM_STATE reached this process for their "
                                               "capture instants (it fell behind physics, or "
                                               "the datagrams were dropped)",
                                               lost - lost_before, state.sim_time, lost));
        }
        using Verdict = VisionEmulator::Verdict;
        switch (outcome.verdict) {
          case Verdict::Invalid:
            bad_content.warn("invalid", "skipped a SIM_STATE: " + outcome.problem);
            break;
          case Verdict::OutOfOrder:
            bad_content.warn("out_of_order", "skipped a SIM_STATE older than one already used");
            break;
          case Verdict::Reset:
            spdlog::info("sim time went back to {} s: simulation reset, pending frames dropped",
                         state.sim_time);
            publish_schedule(state, outcome.frames, true);
            break;
          case Verdict::Repeated:
            break;
          case Verdict::Used:
            publish_schedule(state, outcome.frames, false);
            break;
        }
        for (const vision_frame_t& frame : outcome.frames) bus.publish(vision_channel, frame);
      }));
  bus.subscribe<field_geometry_t>(
      options.channels(Channel::SimGeometry),
      std::function<void(const field_geometry_t&)>([&](const field_geometry_t& geometry) {
        const auto before = emulator.stats().geometry_invalid;
        if (emulator.on_field_geometry(geometry)) {
          spdlog::info("field '{}' ({} x {} m), ball radius {} m", geometry.name,
                       geometry.field_length, geometry.field_width, geometry.ball_radius);
          publish_geometry();
        } else if (emulator.stats().geometry_invalid != before) {
          bad_content.warn("geometry", "ignored an invalid SIM_GEOMETRY");
        }
      }));

  // Robot types defined at run time (e.g. SSL robot specs): the same text
  // physics builds the robots from gives their size here.
  bus.subscribe<sim_control_t>(
      options.channels(Channel::SimControl),
      std::function<void(const sim_control_t&)>([&](const sim_control_t& request) {
        if (request.action != sim_control_t::DEFINE_ROBOT_TYPE) return;
        try {
          const RobotTypeConfig type =
              parse_robot_type_definition(request.robot_type_name, request.robot_type_config);
          if (!emulator.define_robot_size(
                  type.name, RobotSize{type.radius, type.height, type.front_distance})) {
            bad_content.warn("robot_types", "too many robot types defined; ignored " + type.name);
            return;
          }
          spdlog::info("robot type {} defined: radius {} m, height {} m", type.name, type.radius,
                       type.height);
        } catch (const std::exception& error) {
          bad_content.warn("robot_type",
                           std::string("ignored a robot type definition: ") + error.what());
        }
      }));

  // Realism changed at run time (e.g. an SSL realism preset through the bridge).
  bus.subscribe<emulator_realism_t>(
      options.channels.emulator_realism(),
      std::function<void(const emulator_realism_t&)>([&](const emulator_realism_t& realism) {
        const std::string problem = emulator.apply_realism(realism);
        if (!problem.empty()) {
          bad_content.warn("realism",
                           "ignored a realism change from '" + realism.sender + "': " + problem);
          return;
        }
        demand_renewal = 0;  // the latency changed: so did the frames' publication times
        const VisionProfile& p = emulator.profile();
        spdlog::info(
            "realism from '{}': robot sigma {} m / {} rad, ball sigma {} m, detection {} / {}, "
            "false balls {}/s, latency {} s, camera overlap {} m, position error {} m, object "
            "offset {} m, ball area sigma {}",
            realism.sender, p.robot_sigma_x, p.robot_sigma_orientation, p.ball_sigma_x,
            p.robot_detection_probability, p.ball_detection_probability, p.false_ball_rate,
            realism.vision_latency, p.camera_overlap, p.camera_position_error,
            p.object_position_offset, p.ball_area_sigma);
      }));

  // New cameras at run time (e.g. the calibrations of an SSL client's geometry).
  bus.subscribe<vision_cameras_t>(
      options.channels.vision_cameras(),
      std::function<void(const vision_cameras_t&)>([&](const vision_cameras_t& cameras) {
        const std::string problem = emulator.apply_cameras(cameras);
        if (!problem.empty()) {
          bad_content.warn("cameras",
                           "ignored a camera set from '" + cameras.sender + "': " + problem);
          return;
        }
        demand_renewal = 0;  // other capture instants: other states needed
        spdlog::info("cameras from '{}': {} camera(s), overlap {} m", cameras.sender,
                     emulator.camera_count(), emulator.profile().camera_overlap);
        for (std::size_t i = 0; i < emulator.camera_count(); ++i) {
          const PinholeCamera& c = emulator.camera(i).truth();
          spdlog::info("camera {}: at ({}, {}, {}) m, f {} px", emulator.camera(i).id(),
                       c.position().x(), c.position().y(), c.position().z(),
                       c.intrinsics().focal_length);
        }
        publish_geometry();  // the new calibrations, at once
      }));

  // Ask physics for the field now rather than waiting for its next periodic message.
  sim_control_t request{};
  request.request_id = 1;
  request.sender = "ubersim_vision";
  request.action = sim_control_t::REQUEST_GEOMETRY;
  bus.publish(options.channels(Channel::SimControl), request);
  publish_geometry();

  while (!shutdown.requested()) {
    const auto wait =
        std::chrono::duration_cast<std::chrono::milliseconds>(next_geometry - Clock::now());
    bus.wait_and_handle(static_cast<int>(std::clamp<std::int64_t>(wait.count(), 0, 100)),
                        &shutdown);
    repeat_schedule();
    if (Clock::now() >= next_geometry) {
      publish_geometry();
      if (!emulator.field()) next_geometry = Clock::now() + geometry_period;
    }
  }
  handle_what_waits(bus);
  log_summary(emulator.stats(), bus.malformed_count());
  return 0;
}

}  // namespace ubersim::vision
