#pragma once
// The newest of everything the page shows, kept by the LCM thread. The page is
// sent snapshots of it at the display rate, never every message: a frame
// replaces the last one, so a slow page costs nothing but skipped frames.
#include <array>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/referee_t.hpp>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/vision_frame_t.hpp>
#include <ubersim/vision_geometry_t.hpp>

#include "ubersim/viewer/rate_meter.hpp"

namespace ubersim::viewer {

class ViewerModel {
 public:
  using Clock = RateMeter::Clock;

  void on_sim_state(const sim_state_t& state, Clock::time_point now);
  void on_vision(const vision_frame_t& frame, Clock::time_point now);
  void on_vision_geometry(const vision_geometry_t& geometry, Clock::time_point now);
  void on_sim_geometry(const field_geometry_t& field, Clock::time_point now);
  void on_radio(int team, const radio_packet_t& packet, Clock::time_point now);
  void on_ack(const sim_control_ack_t& ack);
  // The game state (REFEREE): the newest is shown until another comes.
  void on_referee(const referee_t& referee, Clock::time_point now);

  // {"type":"frame", "state", "vision": [newest frame per camera], "commands": {yellow, blue},
  //  "geometry", "cameras", "referee" (null before any), "rates": {channel: Hz}, "ack",
  //  "server": {...}} as text.
  std::string snapshot(Clock::time_point now, const nlohmann::json& server_info);
  // True when something arrived since the last snapshot.
  bool changed() const { return changed_; }

  // Channel names shown next to the rates (the names actually subscribed to).
  void set_channel_names(std::map<std::string, std::string> base_to_actual) {
    channel_names_ = std::move(base_to_actual);
  }

 private:
  RateMeter& meter(const std::string& base_name) { return rates_[base_name]; }

  nlohmann::json state_ = nullptr;
  std::map<int, nlohmann::json> vision_by_camera_;
  std::array<nlohmann::json, 2> commands_{nullptr, nullptr};
  nlohmann::json geometry_ = nullptr;
  bool geometry_from_vision_ = false;  // vision's geometry is what control software sees
  nlohmann::json cameras_ = nlohmann::json::array();
  nlohmann::json ack_ = nullptr;
  nlohmann::json referee_ = nullptr;
  std::map<std::string, RateMeter> rates_;
  std::map<std::string, std::string> channel_names_;
  double last_sim_time_ = -1;
  bool changed_ = false;
};

}  // namespace ubersim::viewer
