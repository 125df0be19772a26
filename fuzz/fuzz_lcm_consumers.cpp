// Fuzz target: what the automatic referee, the viewer and the SSL bridge do
// with their LCM input. Each input is one datagram on one channel
// (consumer_inputs.hpp), decoded as the processes decode it (decode_bounded)
// and given to every one of the three that reads that channel, between real
// Division B traffic before it and after it:
//  * referee: StateJudge, what `ubersim_referee auto` does with each
//    SIM_STATE (the AutoReferee, REFEREE, the restart's placement with the
//    radius of each robot type, RobotRadii, the event log), on the field
//    SIM_GEOMETRY gave it;
//  * viewer: ViewerModel and the snapshot text it pushes to pages;
//  * SSL bridge: detection and geometry packets, tracked frames (TrackedFrames),
//    the state it keeps (LatestState) and the game controller's Referee packet
//    (RefereeTranslator).
// What must hold for every input: nothing crashes, throws, leaks or allocates
// beyond the fuzz build's limits; what goes out on LCM encodes and is finite;
// the viewer's snapshot is JSON; every SSL packet serializes.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/referee_t.hpp>
#include <ubersim/sim_control_ack_t.hpp>

#include "consumer_inputs.hpp"
#include "fuzz_support.hpp"
#include "ubersim/bounded_decode.hpp"
#include "ubersim/referee/robot_radii.hpp"
#include "ubersim/referee/state_judge.hpp"
#include "ubersim/sim_clock.hpp"
#include "ubersim/ssl_bridge/latest_state.hpp"
#include "ubersim/ssl_bridge/referee_translation.hpp"
#include "ubersim/ssl_bridge/tracked_frames.hpp"
#include "ubersim/ssl_bridge/vision_translation.hpp"
#include "ubersim/viewer/viewer_model.hpp"

namespace {

using ubersim::fuzz::ConsumerInput;
using Clock = ubersim::viewer::ViewerModel::Clock;

constexpr double kRobotRadius = 0.09;  // m, the bridge's geometry: the largest SSL robot

bool finite(double value) {
  return std::isfinite(value);
}

void check(const ubersim::referee_t& message) {
  if (!finite(message.sim_time) || !finite(message.stage_time_left) ||
      !finite(message.next_judge_time) || !finite(message.command_time) ||
      !finite(message.action_time_left) || !finite(message.designated_position[0]) ||
      !finite(message.designated_position[1])) {
    std::abort();
  }
  ubersim::fuzz::encode_or_abort(message);
}

void check(const ubersim::sim_control_t& placement) {
  bool ok = true;
  for (const ubersim::robot_placement_t& r : placement.robots) {
    ok = ok && finite(r.x) && finite(r.y) && finite(r.orientation) && finite(r.vx) &&
         finite(r.vy) && finite(r.omega);
  }
  for (double v : placement.ball.position) ok = ok && finite(v);
  for (double v : placement.ball.linear_velocity) ok = ok && finite(v);
  if (!ok) std::abort();
  ubersim::fuzz::encode_or_abort(placement);
}

void check(const google::protobuf::Message& packet) {
  if (!packet.IsInitialized()) std::abort();
  (void)packet.SerializeAsString();
}

// The bridge's default ball (its --ball), for kick predictions and geometry.
const ubersim::ssl::BallModel& ball_model() {
  static const ubersim::ssl::BallModel model =
      ubersim::ssl::load_ball_model(UBERSIM_FUZZ_CONFIG_DIR, "ssl_golf_ball");
  return model;
}

void check_finite(const Vector2& v) {
  if (!finite(v.x()) || !finite(v.y())) std::abort();
}
void check_finite(const Vector3& v) {
  if (!finite(v.x()) || !finite(v.y()) || !finite(v.z())) std::abort();
}

// Tracked frames: the same for ground truth.
void check_finite(const TrackerWrapperPacket& packet) {
  const TrackedFrame& f = packet.tracked_frame();
  if (!finite(f.timestamp())) std::abort();
  for (const TrackedBall& b : f.balls()) {
    check_finite(b.pos());
    if (b.has_vel()) check_finite(b.vel());
  }
  for (const TrackedRobot& r : f.robots()) {
    check_finite(r.pos());
    if (!finite(r.orientation()) || !finite(r.vel_angular())) std::abort();
    if (r.has_vel()) check_finite(r.vel());
  }
  if (f.has_kicked_ball()) {
    const KickedBall& k = f.kicked_ball();
    check_finite(k.pos());
    check_finite(k.vel());
    if (!finite(k.start_timestamp())) std::abort();
    if (k.has_stop_timestamp() && !finite(k.stop_timestamp())) std::abort();
    if (k.has_stop_pos()) check_finite(k.stop_pos());
  }
  check(packet);
}

// NaN or infinity must not reach SSL software.
void check_finite(const SSL_WrapperPacket& packet) {
  const SSL_DetectionFrame& d = packet.detection();
  bool ok = finite(d.t_capture()) && finite(d.t_sent());
  for (const SSL_DetectionBall& b : d.balls()) {
    ok = ok && finite(b.confidence()) && finite(b.x()) && finite(b.y()) && finite(b.pixel_x()) &&
         finite(b.pixel_y());
  }
  for (const auto* robots : {&d.robots_yellow(), &d.robots_blue()}) {
    for (const SSL_DetectionRobot& r : *robots) {
      ok = ok && finite(r.confidence()) && finite(r.x()) && finite(r.y()) &&
           finite(r.orientation()) && finite(r.pixel_x()) && finite(r.pixel_y());
    }
  }
  if (!ok) std::abort();
  check(packet);
}

// Geometry: every number, and field sizes that were whole millimetres of a
// length (not an int32 that wrapped).
void check_finite_geometry(const SSL_WrapperPacket& packet) {
  const SSL_GeometryData& g = packet.geometry();
  const SSL_GeometryFieldSize& f = g.field();
  bool ok = f.field_length() >= 0 && f.field_width() >= 0 && f.goal_width() >= 0 &&
            f.goal_depth() >= 0 && f.boundary_width() >= 0 && f.penalty_area_depth() >= 0 &&
            f.penalty_area_width() >= 0 && f.center_circle_radius() >= 0 &&
            f.line_thickness() >= 0 && f.goal_center_to_penalty_mark() >= 0 &&
            f.goal_height() >= 0 && finite(f.ball_radius()) && finite(f.max_robot_radius());
  for (const SSL_FieldLineSegment& line : f.field_lines()) {
    ok = ok && finite(line.p1().x()) && finite(line.p1().y()) && finite(line.p2().x()) &&
         finite(line.p2().y()) && finite(line.thickness());
  }
  for (const SSL_FieldCircularArc& arc : f.field_arcs()) {
    ok = ok && finite(arc.radius()) && finite(arc.thickness());
  }
  for (const SSL_GeometryCameraCalibration& c : g.calib()) {
    for (float v : {c.focal_length(), c.principal_point_x(), c.principal_point_y(), c.q0(), c.q1(),
                    c.q2(), c.q3(), c.tx(), c.ty(), c.tz(), c.derived_camera_world_tx(),
                    c.derived_camera_world_ty(), c.derived_camera_world_tz()}) {
      ok = ok && finite(v);
    }
  }
  if (!ok) std::abort();
  check(packet);
}

// The three consumers, fresh for each input.
struct Consumers {
  std::optional<ubersim::referee::StateJudge> judge;
  ubersim::viewer::ViewerModel viewer;
  ubersim::ssl::TrackedFrames tracked{ubersim::ssl::TrackedSettings{60, ball_model(), "fuzz"}};
  ubersim::ssl::RefereeTranslator referee_packets{"fuzz"};
  ubersim::ssl::GeometryExtras extras;
  ubersim::ssl::LatestState latest;
  Clock::time_point now{};

  // The referee's radius per robot type of the state (names from the wire),
  // read from the shipped robot configs as `ubersim_referee auto` does.
  ubersim::referee::RobotRadii radii{UBERSIM_FUZZ_CONFIG_DIR};

  void field(const ubersim::field_geometry_t& field) {
    judge.emplace(ubersim::referee::JudgeOptions{}, field, [this](const std::string& type) {
      const double radius = radii(type);
      if (!(radius > 0 && radius <= 1) ||
          radii.cached() > ubersim::referee::RobotRadii::kMaxTypes) {
        std::abort();
      }
      return radius;
    });
    viewer.on_sim_geometry(field, tick());
  }
  // The viewer keeps only the newest state: it is given the last state before
  // the input and the last after (encoding each one costs most of the time).
  void state(const ubersim::sim_state_t& state, bool to_viewer = true) {
    const auto out = judge->on_state(state);
    if (out.referee) {
      check(*out.referee);
      if (to_viewer) viewer.on_referee(*out.referee, tick());
      // The bridge forwards what the referee publishes.
      check(referee_packets.translate(*out.referee));
    }
    if (out.placement) check(*out.placement);
    if (to_viewer) viewer.on_sim_state(state, tick());
    for (const auto& packet : tracked.on_state(state)) check_finite(packet);
    // The state the bridge keeps for radio packets' t_sent and teleports.
    latest.update(state);
    if (!ubersim::SimClock::valid_time(latest.sim_time())) std::abort();
  }
  void vision(const ubersim::vision_frame_t& frame) {
    viewer.on_vision(frame, tick());
    // The bridge forwards only these (SslBridge::on_vision).
    if (ubersim::ssl::forwardable(frame)) check_finite(ubersim::ssl::detection_packet(frame));
  }
  void vision_geometry(const ubersim::vision_geometry_t& geometry) {
    viewer.on_vision_geometry(geometry, tick());
    // The bridge sends only these (SslBridge::on_geometry).
    if (ubersim::ssl::forwardable(geometry)) {
      check_finite_geometry(ubersim::ssl::geometry_packet(geometry, extras));
    }
  }
  void snapshot() {
    const std::string text = viewer.snapshot(tick(), nlohmann::json::object());
    if (nlohmann::json::parse(text, nullptr, false).is_discarded()) std::abort();
  }
  Clock::time_point tick() { return now += std::chrono::milliseconds(4); }
};

const ubersim::fuzz::ConsumerTraffic& traffic() {
  static const ubersim::fuzz::ConsumerTraffic instance = ubersim::fuzz::division_b_traffic();
  return instance;
}

// One input: the fuzzed datagram amid real traffic, every output checked.
void run(const ubersim::fuzz::ChannelInput<ConsumerInput>& input) {
  const auto& t = traffic();
  const ConsumerInput channel = input.channel;
  const auto decode = [&input](auto& message) {
    return ubersim::decode_bounded(input.bytes, input.length, message);
  };

  Consumers c;
  c.extras.max_robot_radius = kRobotRadius;
  c.extras.ball_model = ball_model();
  c.vision_geometry(t.vision_geometry);
  // The referee starts on the field SIM_GEOMETRY gives it (it asks once).
  ubersim::field_geometry_t field;
  if (channel == ConsumerInput::SimGeometry && decode(field)) {
    c.field(field);
  } else {
    c.field(t.field);
  }
  const std::size_t half = t.states.size() / 2;
  for (std::size_t i = 0; i < half; ++i) c.state(t.states[i], i + 1 == half);
  if (!t.frames.empty()) c.vision(t.frames.front());

  switch (channel) {
    case ConsumerInput::SimState: {
      ubersim::sim_state_t state;
      if (decode(state)) c.state(state);
      break;
    }
    case ConsumerInput::SimGeometry:
      if (decode(field)) c.viewer.on_sim_geometry(field, c.tick());
      break;
    case ConsumerInput::Vision: {
      ubersim::vision_frame_t frame;
      if (decode(frame)) c.vision(frame);
      break;
    }
    case ConsumerInput::VisionGeometry: {
      ubersim::vision_geometry_t geometry;
      if (decode(geometry)) c.vision_geometry(geometry);
      break;
    }
    case ConsumerInput::RadioYellow:
    case ConsumerInput::RadioBlue: {
      ubersim::radio_packet_t packet;
      if (decode(packet)) {
        c.viewer.on_radio(channel == ConsumerInput::RadioYellow ? 0 : 1, packet, c.tick());
      }
      break;
    }
    case ConsumerInput::SimControlAck: {
      ubersim::sim_control_ack_t ack;
      if (decode(ack)) c.viewer.on_ack(ack);
      break;
    }
    case ConsumerInput::Referee:
    case ConsumerInput::Count: {
      ubersim::referee_t referee;
      if (decode(referee)) {
        check(c.referee_packets.translate(referee));
      }
      // The viewer shows what the bus carries, decoded alike.
      if (decode(referee)) c.viewer.on_referee(referee, c.tick());
      break;
    }
  }
  c.snapshot();
  for (std::size_t i = half; i < t.states.size(); ++i) {
    c.state(t.states[i], i + 1 == t.states.size());
  }
  for (std::size_t i = 1; i < t.frames.size(); ++i) c.vision(t.frames[i]);
  c.snapshot();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 0) run(ubersim::fuzz::channel_input<ConsumerInput>(data, size));
  return 0;
}

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ubersim::fuzz::quiet_logging();
  traffic();
  ball_model();
  return 0;
}
