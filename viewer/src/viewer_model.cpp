#include "ubersim/viewer/viewer_model.hpp"

#include <cmath>

#include "ubersim/viewer/json_encoding.hpp"

namespace ubersim::viewer {

void ViewerModel::on_sim_state(const sim_state_t& state, Clock::time_point now) {
  meter("SIM_STATE").count(now);
  // A reset starts time again: forget detections and commands of the old run.
  if (state.sim_time < last_sim_time_) {
    vision_by_camera_.clear();
    commands_ = {nullptr, nullptr};
  }
  last_sim_time_ = state.sim_time;
  state_ = encode_sim_state(state);
  changed_ = true;
}

void ViewerModel::on_vision(const vision_frame_t& frame, Clock::time_point now) {
  meter("VISION").count(now);
  vision_by_camera_[frame.camera_id] = encode_vision_frame(frame);
  changed_ = true;
}

void ViewerModel::on_vision_geometry(const vision_geometry_t& geometry, Clock::time_point now) {
  meter("VISION_GEOMETRY").count(now);
  geometry_ = encode_field_geometry(geometry.field);
  geometry_from_vision_ = true;
  cameras_ = encode_cameras(geometry);
  changed_ = true;
}

void ViewerModel::on_sim_geometry(const field_geometry_t& field, Clock::time_point now) {
  meter("SIM_GEOMETRY").count(now);
  // Physics' geometry is the truth, but with vision running the two are the
  // same field; only fall back to it when no vision server describes the field.
  if (!geometry_from_vision_) geometry_ = encode_field_geometry(field);
  changed_ = true;
}

void ViewerModel::on_radio(int team, const radio_packet_t& packet, Clock::time_point now) {
  if (team != 0 && team != 1) return;
  meter(team == 0 ? "RADIO_YELLOW" : "RADIO_BLUE").count(now);
  commands_[static_cast<std::size_t>(team)] = encode_radio_packet(packet);
  changed_ = true;
}

void ViewerModel::on_ack(const sim_control_ack_t& ack) {
  ack_ = encode_ack(ack);
  changed_ = true;
}

void ViewerModel::on_referee(const referee_t& referee, Clock::time_point now) {
  meter("REFEREE").count(now);
  referee_ = encode_referee(referee);
  changed_ = true;
}

std::string ViewerModel::snapshot(Clock::time_point now, const nlohmann::json& server_info) {
  nlohmann::json vision = nlohmann::json::array();
  for (const auto& [camera, frame] : vision_by_camera_) vision.push_back(frame);
  nlohmann::json rates = nlohmann::json::object();
  for (const char* base : {"SIM_STATE", "VISION", "VISION_GEOMETRY", "SIM_GEOMETRY", "RADIO_YELLOW",
                           "RADIO_BLUE", "REFEREE"}) {
    const auto name = channel_names_.find(base);
    const std::string shown = name == channel_names_.end() ? base : name->second;
    rates[shown] = std::round(meter(base).rate(now) * 10) / 10;
  }
  changed_ = false;
  const nlohmann::json frame = {
      {"type", "frame"},       {"state", state_},
      {"vision", vision},      {"commands", {{"yellow", commands_[0]}, {"blue", commands_[1]}}},
      {"geometry", geometry_}, {"cameras", cameras_},
      {"referee", referee_},   {"rates", rates},
      {"ack", ack_},           {"server", server_info}};
  // LCM strings (robot types, the field's name, ack messages) are bytes from
  // anyone on the bus: dump() throws on one that is not UTF-8, which stopped
  // the viewer while a page was open. Such bytes become U+FFFD instead (fuzz_lcm_consumers).
  return frame.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace ubersim::viewer
