#pragma once
// The vision emulator without its process around it: feed it every SIM_STATE
// and SIM_GEOMETRY, publish what it hands back (the same shape as the physics
// and radio cores: docs/design.md, "One shape for the cores"). All timing is in sim time
// (docs/design.md, Time), so the output depends only on the profile, the seed and
// the stream of states, never on how fast physics runs or on the wall clock.
//
// Per state: check it (a bad one is counted and skipped), follow sim time
// (an older step is out of order and skipped; a step back to 0..2 is a reset),
// let each camera capture if one of its instants falls on this step, then
// release every frame whose publication time has come (camera by camera in id
// order, each camera's frames oldest first).
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <ubersim/emulator_realism_t.hpp>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/truth_demand_t.hpp>
#include <ubersim/vision_cameras_t.hpp>
#include <ubersim/vision_frame_t.hpp>
#include <ubersim/vision_geometry_t.hpp>
#include <vector>

#include "ubersim/delay_line.hpp"
#include "ubersim/sim_clock.hpp"
#include "ubersim/vision/camera_detector.hpp"
#include "ubersim/vision/capture_schedule.hpp"
#include "ubersim/vision/random_source.hpp"
#include "ubersim/vision/robot_sizes.hpp"
#include "ubersim/vision/vision_profile.hpp"

namespace ubersim::vision {

struct VisionStats {
  std::uint64_t states_used = 0;          // advanced sim time (resets included)
  std::uint64_t states_invalid = 0;       // content check failed: skipped
  std::uint64_t states_out_of_order = 0;  // older than one already used: skipped
  std::uint64_t states_repeated = 0;      // same step again (physics paused): ignored
  std::uint64_t resets = 0;
  std::uint64_t frames_captured = 0;
  std::uint64_t frames_published = 0;
  std::uint64_t frames_dropped_at_reset = 0;  // pending frames of a world that was reset
  std::uint64_t capture_instants_missed = 0;  // no state arrived for them
  std::uint64_t geometry_invalid = 0;
  std::uint64_t camera_sets_applied = 0;
  std::uint64_t camera_sets_invalid = 0;         // VISION_CAMERAS refused whole
  std::uint64_t frames_dropped_with_camera = 0;  // pending frames of a camera taken away
};

class VisionEmulator {
 public:
  enum class Verdict { Used, Reset, Repeated, OutOfOrder, Invalid };
  // What one state produced: what became of it, and the frames to publish.
  struct Output {
    Verdict verdict = Verdict::Used;
    std::string problem;                 // why an invalid state was skipped
    std::vector<vision_frame_t> frames;  // to publish now, in order
  };

  VisionEmulator(VisionProfile profile, RobotSizes robot_sizes);

  Output on_sim_state(const sim_state_t& state);

  // Returns true when the geometry was new (different from the last one).
  // An invalid geometry is counted and ignored (returns false).
  bool on_field_geometry(const field_geometry_t& geometry);
  const std::optional<field_geometry_t>& field() const { return field_; }

  // Field plus the camera calibrations as the vision system believes them;
  // the field is empty (name "") until one is known.
  vision_geometry_t geometry_message() const;

  // A robot type defined at run time: its robots are seen with this size.
  bool define_robot_size(const std::string& type, const RobotSize& size) {
    return robot_sizes_.define(type, size);
  }

  // A run-time realism change (EMULATOR_REALISM): the values >= 0 replace
  // the profile's from the next capture on (frames already captured keep
  // their timing). Returns what was wrong (nothing applied), or "".
  std::string apply_realism(const emulator_realism_t& realism);

  // A new camera set at run time (VISION_CAMERAS): every camera is replaced
  // from the next capture on. A camera id already in use keeps its capture
  // schedule, frame numbers, timing and random streams; a new id captures at
  // the rate, phase and timing of the current first camera (all cameras of a
  // set from the SSL protocol capture together, as in the ER-Force
  // simulator). Frames still pending for a camera that is gone are dropped
  // (counted). Without a camera overlap set so far, ER-Force's default
  // (kErForceDefaultCameraOverlap) decides which camera sees what. Returns
  // what was wrong (nothing applied), or "".
  std::string apply_cameras(const vision_cameras_t& cameras);

  // Earliest sim time at which a frame not yet published can be published
  // (frames waiting for their release, and the next capture of each camera
  // with its latency, drawn ahead). +inf before the first state. Sync mode
  // bounds how far physics may run on it (docs/sync.md).
  double next_publication() const;
  // Next capture instant of any camera (+inf before the first state).
  double next_capture() const;
  // The ground truth this emulator needs (SIM_TRUTH_DEMAND, for physics
  // --truth-on-demand): each camera's capture instants, the publication
  // times of the frames waiting, and those of each camera's next
  // kFramesAhead frames (their latency jitter is drawn that far ahead), so
  // that one demand holds for several frames.
  truth_demand_t truth_demand() const;
  // Sim time from which a demand made now no longer covers two frames ahead
  // of some camera: the process announces the next one at the first state at
  // or after it. 0 before the first state (renew at once).
  double demand_renewal_time() const;
  static constexpr std::size_t kFramesAhead = 8;

  const VisionProfile& profile() const { return profile_; }
  const VisionStats& stats() const { return stats_; }
  double sim_time() const { return clock_.now(); }
  std::size_t camera_count() const { return cameras_.size(); }
  const CameraDetector& camera(std::size_t index) const { return cameras_.at(index).detector; }

 private:
  struct Camera {
    CameraDetector detector;
    CaptureSchedule schedule;
    RandomSource latency_random;
    // The latency jitter (standard normal) of the next kFramesAhead frames,
    // the next one first: drawn ahead so that their publication times are
    // known before their capture. Drawn in capture order from one source,
    // so the jitter of each frame does not depend on how far ahead it is.
    std::deque<double> upcoming_jitter;
    DelayLine<vision_frame_t> pending;
    CameraProfile timing;  // rate, phase, latency of this camera
  };

  const WorldSnapshot& snapshot(const sim_state_t& state);
  double release_time(Camera& camera, double t_capture);
  // Latency of the camera's frame `ahead` captures from now (0: the next).
  static double latency_of(const Camera& camera, std::size_t ahead = 0);
  void restart_after_reset();
  // Every camera's region (profile_.camera_overlap) after a change of cameras or overlap.
  void update_regions();
  Camera make_camera(const CameraProfile& c) const;
  void check_step_fits(const sim_state_t& state);
  struct DueCapture {
    Camera* camera;
    CaptureSchedule::Capture capture;
  };
  // FRAME_NUMBERS = shared: one number for the captures of one step.
  void share_frame_number(std::vector<DueCapture>& due);

  VisionProfile profile_;
  RobotSizes robot_sizes_;
  std::vector<Camera> cameras_;
  SimClock clock_;
  std::optional<field_geometry_t> field_;
  double ball_radius_;
  WorldSnapshot world_;
  bool step_checked_ = false;
  std::int64_t next_shared_frame_number_ = 0;
  VisionStats stats_;
};

}  // namespace ubersim::vision
