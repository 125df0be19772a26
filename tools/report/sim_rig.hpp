#pragma once
// The whole process set a control program talks to — the real ubersim_physics,
// ubersim_vision and ubersim_radio over real LCM — run in lockstep so that an
// experiment is exact in simulation time however loaded the machine is.
//
// The report stands where a team's control software stands: it publishes
// radio_packet_t on RADIO_YELLOW and reads vision_frame_t on VISION. To know
// when everything has caught up with a step, without changing what it measures:
//  * vision: the vision profile gets one extra "marker" camera (the highest id:
//    240 Hz, no latency). Frames go out camera by camera in id order, so once the
//    marker's frame for step s is here, every frame published at step s is too.
//    The marker sees nothing and its frames are not passed on. Cameras draw
//    from their own random streams, so it changes no other camera's output.
//  * radio: after each yellow packet the rig pings through the blue team's link
//    (profile `ideal`: forwarded at once) to a blue robot parked out of the way.
//    The emulator handles its input in order, so once the ping is on
//    SIM_COMMANDS the yellow packet has been through the emulated link (or been
//    lost in it, as the profile says).
//  * physics (--lockstep) advances only on SIM_CONTROL STEP and acknowledges it.
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_commands_t.hpp>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/vision_frame_t.hpp>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/child_process.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/truth_demand_announcer.hpp"

namespace ubersim::report {

// Where the programs, the config and the scratch files are.
struct RigPaths {
  std::string bin_dir;                     // ubersim_physics, ubersim_vision, ubersim_radio
  std::string config_dir;                  // the config/ folder
  std::string work_dir;                    // generated config files and the processes' logs
  std::string physics_config = "default";  // ubersim_physics --physics-config (name or path)
};

struct RigOptions {
  std::string name = "rig";  // prefix of the log files in work_dir
  // Scenario (name or path). It must have a BLUE_0 robot: the rig's ping robot.
  std::string scenario;
  std::string vision_profile = "cmdragons02";  // name or path
  std::string radio_profile = "cmdragons02";   // the yellow team's link (name or path)
  std::uint64_t vision_seed = 2002;
  std::uint64_t radio_seed = 2002;
};

class SimRig {
 public:
  // Starts the three processes and waits until each answers. Throws
  // std::runtime_error (with the process's log) when one does not.
  SimRig(const RigPaths& paths, const RigOptions& options);
  ~SimRig();
  SimRig(const SimRig&) = delete;
  SimRig& operator=(const SimRig&) = delete;

  // Each step's SIM_STATE once (not the repeats physics publishes after a
  // placement or while idle), and every camera frame (marker frames excluded).
  void on_state(std::function<void(const sim_state_t&)> handler);
  void on_frame(std::function<void(const vision_frame_t&)> handler);

  // SIM_CONTROL PLACE / SETUP; waits for the acknowledgement, throws if refused.
  void place(sim_control_t request);
  // Publishes a yellow radio packet (team, sequence and count are filled in)
  // and waits until the radio emulator has handled it.
  void send(radio_packet_t packet);
  // Advances physics by `steps` and waits until vision has handled the last one.
  void step(int steps);

  double time() const { return state_.sim_time; }  // s, latest SIM_STATE
  std::int64_t step_index() const { return state_.step; }
  double dt() const { return state_.dt; }              // s
  const sim_state_t& state() const { return state_; }  // latest

  // Stops the processes (SIGTERM) and returns "" if all exited with 0, else a
  // description with their logs. Called by the destructor if not before.
  std::string stop();

 private:
  bool control(sim_control_t request, double timeout_s, sim_control_ack_t* ack = nullptr);
  bool ping_radio(double timeout_s);
  void raw_step(int steps);
  template <class Done>
  bool wait(Done done, double timeout_s);
  [[noreturn]] void fail(const std::string& what);
  // Writes the vision profile plus the marker camera; returns its path.
  std::string write_marker_profile(const std::string& base_profile);

  RigPaths paths_;
  RigOptions options_;
  ChannelNames channels_;
  std::string sender_;
  std::unique_ptr<MessageBus> bus_;
  // Every step's state (lockstep publishes each step anyway; said all the same,
  // so that the rig does not depend on that).
  std::unique_ptr<TruthDemandAnnouncer> truth_demand_;
  std::unique_ptr<ChildProcess> physics_, vision_, radio_;
  std::vector<std::function<void(const sim_state_t&)>> state_handlers_;
  std::vector<std::function<void(const vision_frame_t&)>> frame_handlers_;
  std::map<std::int64_t, sim_control_ack_t> acks_;
  sim_state_t state_{};
  std::int64_t dispatched_step_ = -1;  // step of the last state passed to the handlers
  int marker_camera_ = -1;
  double marker_time_ = -1;  // t_capture of the newest marker frame (s)
  std::int64_t request_id_ = 0;
  std::int64_t yellow_sequence_ = 0;
  std::int64_t ping_sequence_ = 0;
  std::int64_t ping_forwarded_ = -1;
  bool stopped_ = false;
};

}  // namespace ubersim::report
