#pragma once
// Tracked frames (--tracked): SSL-Vision's tracker protocol (TrackerWrapperPacket,
// 224.5.23.2:10010 by convention) built from ground truth (SIM_STATE), each
// frame published once sim time has passed its timestamp by the vision
// latency the bridge observes, so tracked data is as late as the detections.
// A kick is seen as a jump of the ball's speed next to a robot; its stop is
// predicted with the ball config's two-phase model.
#include <ssl_vision_wrapper_tracked.pb.h>

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <ubersim/sim_state_t.hpp>

#include "ubersim/ssl_bridge/vision_translation.hpp"

namespace ubersim::ssl {

struct TrackedSettings {
  double rate = 60;                     // Hz of sim time, frames per second
  std::optional<BallModel> ball_model;  // for the kicked ball's stop prediction
  std::string uuid;                     // constant while the bridge runs
};

class TrackedFrames {
 public:
  explicit TrackedFrames(TrackedSettings settings);

  // A new SIM_STATE; returns the packets due now (oldest first). A state with
  // a number that is not finite or beyond 1e9, or a time not valid
  // (sim_state_numbers_fit), is refused: counted
  // in refused(), never sent, and it changes nothing.
  std::vector<TrackerWrapperPacket> on_state(const sim_state_t& state);
  std::uint64_t refused() const { return refused_; }
  // The latency vision frames show (s, sim time): tracked frames wait as long.
  void set_latency(double latency) { latency_ = latency; }
  double latency() const { return latency_; }

 private:
  TrackerWrapperPacket build(const sim_state_t& state);
  void detect_kick(const sim_state_t& state);

  TrackedSettings settings_;
  double latency_ = 0;
  double next_sample_ = 0;  // s, sim time of the next frame
  uint32_t frame_number_ = 0;
  std::deque<sim_state_t> waiting_;
  std::optional<KickedBall> kick_;
  double previous_ball_speed_ = 0;
  double previous_time_ = -1;
  std::uint64_t refused_ = 0;
};

// A version-4 UUID (a source's id for this run): random, as a real tracker's;
// with a seed, the same on every run with that seed and `purpose` (the
// bridge's --seed: reruns then send the teams the same bytes).
std::string make_uuid(std::optional<std::uint64_t> seed = std::nullopt, std::uint64_t purpose = 0);

}  // namespace ubersim::ssl
