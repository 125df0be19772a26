#pragma once
#include "child_process.hpp"
// What the end-to-end vision tests share: the real ubersim_vision process as
// a child, and a driver that stands in for physics. The driver publishes
// ground truth on SIM_STATE step by step (240 Hz in sim time) and collects
// what the emulator publishes, over real LCM multicast.
//
// Lockstep: a test profile may add a "marker" camera with the highest id that
// captures at every physics step with zero latency. Its frame for step s is
// the emulator's last publication while handling step s (frames of one step go
// out camera by camera in id order), so the driver publishes step s + 1 only
// after it, no state is ever lost, and every other frame is known to have
// been published at step s: publication time is measured exactly, in sim time.
#include <sys/types.h>

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/vision_cameras_t.hpp>
#include <ubersim/vision_frame_t.hpp>
#include <ubersim/vision_geometry_t.hpp>
#include <vector>

#include "temp_dir.hpp"
#include "ubersim/channels.hpp"
#include "ubersim/message_bus.hpp"

namespace vision_test {

constexpr double kDt = 1.0 / 240;  // s, the physics step the driver stands in for

std::string vision_program();
std::string config_dir();
std::string read_text(const std::string& path);

using TempDir = ubersim::test::TempDir;

using ubersim::test::ChildProcess;  // tests/support

// Keys that add the lockstep marker camera as camera `id` (see the top).
std::string marker_camera_keys(int id);

// The counts ubersim_vision logs on exit ("summary: ..."); -1 where absent.
std::map<std::string, long> exit_summary(const std::string& log_text);

struct TruthRobot {
  std::int8_t team = 0;
  std::int32_t id = 0;
  double x = 0;            // m
  double y = 0;            // m
  double orientation = 0;  // rad
  std::string type = "omni4_ssl";
};
struct Truth {
  std::vector<TruthRobot> robots;
  bool ball_present = false;
  Eigen::Vector3d ball = Eigen::Vector3d(0, 0, 0.0215);  // centre (m)
};
using World = std::function<Truth(double t)>;

ubersim::sim_state_t make_state(std::int64_t step, const Truth& truth);
ubersim::field_geometry_t division_b_geometry();

struct Received {
  ubersim::vision_frame_t frame;
  std::int64_t published_at_step = -1;  // known in lockstep only
};

class SimDriver {
 public:
  SimDriver();

  // Waits for the emulator's REQUEST_GEOMETRY on SIM_CONTROL (it is then
  // subscribed) and answers with `geometry` on SIM_GEOMETRY, as physics does.
  bool wait_for_emulator(const ubersim::field_geometry_t& geometry, double timeout_s = 15);

  // Publishes steps first..last; after each, waits for the marker camera's
  // frame of that step. False (with a message in failure()) on a timeout.
  bool run_lockstep(std::int64_t first, std::int64_t last, const World& world, int marker);
  // Publishes steps first..last as fast as the emulator keeps up: never more
  // than `lead` s of sim time ahead of the newest capture heard from each of
  // cameras 0..camera_count-1.
  bool run_windowed(std::int64_t first, std::int64_t last, const World& world, double lead,
                    int camera_count);

  void publish_state(const ubersim::sim_state_t& state);
  void publish_raw_state(const std::vector<std::uint8_t>& bytes);
  void publish_geometry(const ubersim::field_geometry_t& geometry);
  // A new camera set on VISION_CAMERAS, as the SSL bridge sends one.
  void publish_cameras(const ubersim::vision_cameras_t& cameras);
  // Handles whatever arrives for a while (wall-clock seconds).
  void listen(double seconds);

  std::vector<Received> frames(int camera) const;
  const std::vector<ubersim::vision_geometry_t>& geometries() const { return geometries_; }
  const std::string& failure() const { return failure_; }

 private:
  void on_frame(const ubersim::vision_frame_t& frame);
  bool wait_for(const std::function<bool()>& done, double timeout_s);

  ubersim::MessageBus bus_;
  ubersim::ChannelNames channels_;
  int marker_ = -1;
  std::int64_t current_step_ = -1;  // the step published last
  double current_time_ = -1;
  bool marker_seen_ = false;  // the marker frame of current_step_ arrived
  std::vector<ubersim::vision_frame_t> since_marker_;
  std::vector<Received> received_;
  std::map<int, double> newest_capture_;
  std::vector<ubersim::vision_geometry_t> geometries_;
  bool emulator_ready_ = false;
  std::string failure_;
};

}  // namespace vision_test
