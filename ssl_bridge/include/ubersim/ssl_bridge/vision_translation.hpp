#pragma once
// VISION / VISION_GEOMETRY (SI units) -> SSL-Vision wrapper packets (mm).
#include <messages_robocup_ssl_wrapper.pb.h>

#include <optional>
#include <string>
#include <ubersim/vision_frame_t.hpp>
#include <ubersim/vision_geometry_t.hpp>

namespace ubersim::ssl {

// The straight-kick ball model of our ball config, as SSL geometry reports it.
struct BallModel {
  double sliding_deceleration = 0;  // m/s^2, positive
  double rolling_deceleration = 0;  // m/s^2, positive
  double slide_to_roll_ratio = 0;   // unitless
};

// The model of a ball config (config/balls/NAME.cfg); throws ConfigError.
BallModel load_ball_model(const std::string& config_dir, const std::string& name);

struct GeometryExtras {
  std::optional<BallModel> ball_model;
  double max_robot_radius = 0;  // m, 0 = not reported
};

// The SSL_Source every packet carries: ubersim is neither SSL-Vision nor grSim
// nor the ER-Force simulator, and tools that act on those values expect those
// programs' behaviour, so OTHER is the honest value.
inline constexpr SSL_Source kPacketSource = SSL_SOURCE_OTHER;

// Whether a VISION frame may go out as a detection packet: every number finite
// and small enough to stay finite as SSL's float millimetres. ubersim's vision
// never sends another, but anyone on the bus may, and SSL software is not
// written for NaN; the bridge counts and drops such frames (fuzz_lcm_consumers).
bool forwardable(const vision_frame_t& frame);
// The same for VISION_GEOMETRY: every number the geometry packet carries fits
// (fits_ssl), field sizes are lengths from 0 to 1e6 m (SSL sends them as int32
// whole millimetres) and image sizes are not negative. The bridge counts and
// drops another and keeps the last good geometry.
bool forwardable(const vision_geometry_t& geometry);
SSL_WrapperPacket detection_packet(const vision_frame_t& frame);
SSL_WrapperPacket geometry_packet(const vision_geometry_t& geometry, const GeometryExtras& extras);

}  // namespace ubersim::ssl
