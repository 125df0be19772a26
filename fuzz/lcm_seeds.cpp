// Real messages for the LCM fuzz targets: a state of the Division B scenario
// as its World fills it, commands as the radio emulator forwards them, the
// control requests the referee and the SSL bridge send, the sync and truth
// messages of a sync run, and a default message of every other type (so every
// type has a seed). Inputs are one selector byte and then the encoded message.
#include "lcm_seeds.hpp"

#include <cstdint>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <ubersim/emulator_realism_t.hpp>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/referee_t.hpp>
#include <ubersim/sim_commands_t.hpp>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/sync_horizon_t.hpp>
#include <ubersim/truth_demand_t.hpp>
#include <ubersim/vision_cameras_t.hpp>
#include <ubersim/vision_schedule_t.hpp>
#include <utility>

#include "consumer_inputs.hpp"
#include "emulator_inputs.hpp"
#include "fuzz_support.hpp"
#include "physics_inputs.hpp"
#include "ubersim/config_text.hpp"
#include "ubersim/encoded_bounds.hpp"
#include "ubersim/physics/world.hpp"

namespace ubersim::fuzz {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& dir, const std::string& name, std::uint8_t selector,
           const std::string& bytes) {
  fs::create_directories(dir);
  std::ofstream out(dir / name, std::ios::binary);
  out.put(static_cast<char>(selector));
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + (dir / name).string());
}

// The selector fuzz_lcm_decode reads for Msg: its index in AllLcmTypes.
template <class Msg, class... Msgs>
std::uint8_t type_index(LcmTypeList<Msgs...>) {
  std::uint8_t index = 0;
  bool found = false;
  ((found = found || std::is_same_v<Msg, Msgs>, index += found ? 0 : 1), ...);
  return index;
}

template <class Msg>
void write_decode_seed(const fs::path& dir, const std::string& name, const Msg& message) {
  write(dir, name, type_index<Msg>(AllLcmTypes{}), encode_or_abort(message));
}

template <class... Msgs>
void write_default_seeds(const fs::path& dir, LcmTypeList<Msgs...>) {
  (write_decode_seed(dir, std::string(Msgs::getTypeName()) + "_default", Msgs{}), ...);
}

robot_command_t command(int id, std::int8_t mode, double vx, double omega, double kick) {
  robot_command_t c{};
  c.robot_id = id;
  c.mode = mode;
  c.vx = vx;
  c.omega = omega;
  c.kick_speed = kick;
  if (mode == robot_command_t::MODE_WHEEL_SPEEDS) {
    c.wheel_speeds = {20.0, -20.0, -20.0, 20.0};
    c.num_wheels = 4;
  }
  return c;
}

sim_commands_t commands() {
  sim_commands_t p{};
  p.team = 1;
  p.sequence = 7;
  p.t_received = 0.004;
  p.t_apply = 0.0125;
  p.command_timeout = 0.5;
  p.commands = {command(0, robot_command_t::MODE_LOCAL_VELOCITY, 1.5, 0.5, 0),
                command(1, robot_command_t::MODE_GLOBAL_VELOCITY, -1.0, 2.0, 4.0),
                command(2, robot_command_t::MODE_WHEEL_SPEEDS, 0, 0, 0)};
  p.commands[0].dribbler_speed = 300;
  p.commands[1].chip_speed = 3;
  p.num_commands = static_cast<std::int32_t>(p.commands.size());
  return p;
}

sim_control_t control(std::int8_t action) {
  sim_control_t c{};
  c.request_id = 1;
  c.sender = "referee";
  c.action = action;
  return c;
}

sim_control_t placement() {
  sim_control_t c = control(sim_control_t::PLACE);
  robot_placement_t robot{};
  robot.team = 0;
  robot.robot_id = 2;
  robot.present = true;
  robot.x = -1.0;
  robot.y = 0.5;
  robot.orientation = 1.2;
  robot.vx = 0.3;
  c.robots = {robot};
  c.num_robots = 1;
  c.has_ball = true;
  c.ball.position[0] = 0.2;
  c.ball.linear_velocity[0] = 3.0;
  c.ball.rolling = true;
  return c;
}

truth_demand_t demand() {
  truth_demand_t d{};
  d.consumer = "vision";
  d.period = {1.0 / 60};
  d.phase = {0.0};
  d.num_periodic = 1;
  d.instants = {0.05, 0.0625};
  d.num_instants = 2;
  return d;
}

sync_horizon_t horizon() {
  sync_horizon_t h{};
  h.sequence = 3;
  h.horizon = 0.05;
  h.held_by = sync_horizon_t::HELD_BY_CLIENT;
  h.waiting_for = "demo yellow";
  h.clients = 2;
  return h;
}

vision_schedule_t schedule() {
  vision_schedule_t s{};
  s.t_state = 0.0375;
  s.step = 9;
  s.next_publication = 0.054;
  s.next_capture = 0.0167;
  s.camera_id = {0};
  s.frame_number = {1};
  s.t_capture = {0.0};
  s.num_frames = 1;
  return s;
}

referee_t referee() {
  referee_t r{};
  r.sim_time = 0.1;
  r.stage = referee_t::STAGE_FIRST_HALF;
  r.stage_time_left = 150;
  r.command = referee_t::NORMAL_START;
  r.ball_in_play = true;
  r.yellow_goalkeeper = 0;
  r.blue_goalkeeper = 0;
  return r;
}

sim_state_t division_b_state() {
  physics::World world(
      physics::load_world_setup(UBERSIM_FUZZ_CONFIG_DIR, "division_b_6v6", "default"));
  world.submit(commands());
  for (int i = 0; i < 24; ++i) world.step();
  sim_state_t state{};
  world.fill_state(state);
  return state;
}

radio_packet_t radio_packet(std::int8_t team) {
  radio_packet_t p{};
  p.team = team;
  p.sequence = 12;
  p.t_sent = 0.0;
  p.commands = commands().commands;
  p.num_commands = static_cast<std::int32_t>(p.commands.size());
  return p;
}

emulator_realism_t realism() {
  emulator_realism_t r{};
  r.request_id = 5;
  r.sender = "ssl bridge";
  r.robot_sigma_position = 0.002;
  r.robot_sigma_orientation = 0.01;
  r.ball_sigma_position = 0.003;
  r.robot_detection_probability = 0.95;
  r.ball_detection_probability = 0.9;
  r.false_ball_rate = 0.1;
  r.ball_min_visible_fraction = 0.4;
  r.vision_latency = 0.035;
  r.vision_processing_time = 0.005;
  r.command_latency = 0.02;
  r.command_robot_loss = 0.05;
  r.feedback_robot_loss = -1;  // keep the profile's
  r.ball_area_sigma = 6.5;
  r.camera_overlap = 1;
  r.camera_position_error = 0.1;
  r.object_position_offset = 0.02;
  return r;
}

// Two cameras as the official Division A geometry places them (6 m up, 3.01 m either
// side of the centre line), looking straight down, no image edge.
vision_cameras_t cameras() {
  vision_cameras_t set{};
  set.request_id = 6;
  set.sender = "ssl bridge";
  for (int id = 0; id < 2; ++id) {
    camera_calibration_t c{};
    c.camera_id = id;
    c.focal_length = 390;
    c.principal_x = c.principal_y = 300;
    c.position[0] = id == 0 ? -3.01 : 3.01;
    c.position[2] = 6;
    c.orientation[1] = 1;  // 180 deg about x: straight down, rows along -y
    c.distortion = 0.2;
    set.cameras.push_back(c);
  }
  set.num_cameras = 2;
  return set;
}

void write_emulator_seeds(const fs::path& dir) {
  const auto on = [](EmulatorInput channel) { return static_cast<std::uint8_t>(channel); };
  write(dir, "radio_yellow", on(EmulatorInput::RadioYellow), encode_or_abort(radio_packet(0)));
  write(dir, "radio_blue", on(EmulatorInput::RadioBlue), encode_or_abort(radio_packet(1)));
  radio_packet_t not_finite = radio_packet(1);
  not_finite.commands[0].omega = std::numeric_limits<double>::quiet_NaN();
  not_finite.commands[2].wheel_speeds[0] = std::numeric_limits<double>::infinity();
  write(dir, "radio_not_finite", on(EmulatorInput::RadioBlue), encode_or_abort(not_finite));
  write(dir, "radio_wrong_team", on(EmulatorInput::RadioYellow), encode_or_abort(radio_packet(1)));
  write(dir, "state", on(EmulatorInput::SimState), encode_or_abort(division_b_state()));
  physics::World world(
      physics::load_world_setup(UBERSIM_FUZZ_CONFIG_DIR, "division_b_6v6", "default"));
  write(dir, "geometry", on(EmulatorInput::SimGeometry), encode_or_abort(world.geometry()));
  write(dir, "realism", on(EmulatorInput::EmulatorRealism), encode_or_abort(realism()));
  write(dir, "cameras", on(EmulatorInput::VisionCameras), encode_or_abort(cameras()));
}

void write_consumer_seeds(const fs::path& dir) {
  const auto on = [](ConsumerInput channel) { return static_cast<std::uint8_t>(channel); };
  const ConsumerTraffic traffic = division_b_traffic();
  write(dir, "state", on(ConsumerInput::SimState), encode_or_abort(division_b_state()));
  sim_state_t out_of_field = traffic.states.back();
  out_of_field.ball.position[0] = 7.0;  // over the goal line: the referee stops the game
  write(dir, "state_ball_out", on(ConsumerInput::SimState), encode_or_abort(out_of_field));
  // The referee looks up each robot type's radius for the restart's placement:
  // names that are no config name (empty, long, not UTF-8, paths), or unknown.
  sim_state_t odd_types = out_of_field;
  odd_types.sim_time = 60;  // past the first stop: the referee places the kick-off
  const char* const names[] = {"",          "omni\xff\xfe",  "../robots/omni4_ssl",
                               "/dev/zero", "omni4_ssl.cfg", "no_such_type"};
  for (std::size_t i = 0; i < odd_types.robots.size(); ++i) {
    odd_types.robots[i].robot_type = i < std::size(names) ? names[i] : std::string(300, 'x');
  }
  write(dir, "state_ball_out_odd_types", on(ConsumerInput::SimState), encode_or_abort(odd_types));
  // More type names than the referee keeps (RobotRadii::kMaxTypes).
  sim_state_t many_types = odd_types;
  while (many_types.robots.size() < 80) {
    robot_state_t robot =
        out_of_field.robots[many_types.robots.size() % out_of_field.robots.size()];
    robot.robot_id = static_cast<std::int32_t>(many_types.robots.size());
    robot.x = -4.0 + 0.25 * static_cast<double>(many_types.robots.size() % 32);
    robot.y = -2.5 + 1.0 * static_cast<double>(many_types.robots.size() / 32);
    many_types.robots.push_back(robot);
  }
  for (std::size_t i = 0; i < many_types.robots.size(); ++i) {
    many_types.robots[i].robot_type = "type_" + std::to_string(i);
  }
  many_types.num_robots = static_cast<std::int32_t>(many_types.robots.size());
  write(dir, "state_ball_out_many_types", on(ConsumerInput::SimState), encode_or_abort(many_types));
  sim_state_t not_finite = traffic.states.back();
  not_finite.ball.position[1] = std::numeric_limits<double>::quiet_NaN();
  not_finite.robots[0].x = std::numeric_limits<double>::infinity();
  write(dir, "state_not_finite", on(ConsumerInput::SimState), encode_or_abort(not_finite));
  not_finite.sim_time = std::numeric_limits<double>::quiet_NaN();  // the SSL bridge drops it
  write(dir, "state_time_not_finite", on(ConsumerInput::SimState), encode_or_abort(not_finite));
  sim_state_t not_utf8 = traffic.states.back();  // once stopped the viewer (docs/fuzzing.md)
  not_utf8.robots[0].robot_type = "omni\xff";
  write(dir, "state_type_not_utf8", on(ConsumerInput::SimState), encode_or_abort(not_utf8));
  write(dir, "geometry", on(ConsumerInput::SimGeometry), encode_or_abort(traffic.field));
  for (std::size_t i = 0; i < traffic.frames.size() && i < 2; ++i) {
    write(dir, "vision_" + std::to_string(i), on(ConsumerInput::Vision),
          encode_or_abort(traffic.frames[i]));
  }
  if (!traffic.frames.empty() && !traffic.frames[0].robots_blue.empty()) {
    vision_frame_t huge = traffic.frames[0];  // the SSL bridge drops it
    huge.robots_blue[0].x = 1e300;
    write(dir, "vision_huge", on(ConsumerInput::Vision), encode_or_abort(huge));
  }
  write(dir, "vision_geometry", on(ConsumerInput::VisionGeometry),
        encode_or_abort(traffic.vision_geometry));
  vision_geometry_t bad_geometry = traffic.vision_geometry;  // the SSL bridge drops it
  bad_geometry.field.ball_radius = std::numeric_limits<double>::quiet_NaN();
  bad_geometry.field.field_length = 1e7;  // 1e10 mm: beyond int32
  if (!bad_geometry.cameras.empty()) bad_geometry.cameras[0].position[2] = 1e300;
  write(dir, "vision_geometry_not_finite", on(ConsumerInput::VisionGeometry),
        encode_or_abort(bad_geometry));
  write(dir, "radio_yellow", on(ConsumerInput::RadioYellow), encode_or_abort(radio_packet(0)));
  write(dir, "radio_blue", on(ConsumerInput::RadioBlue), encode_or_abort(radio_packet(1)));
  sim_control_ack_t ack{};
  ack.request_id = 2;
  ack.sender = "viewer";
  ack.ok = false;
  ack.message = "unknown robot";
  write(dir, "ack", on(ConsumerInput::SimControlAck), encode_or_abort(ack));
  write(dir, "referee", on(ConsumerInput::Referee), encode_or_abort(referee()));
}

}  // namespace

void write_lcm_seeds(const fs::path& decode_dir, const fs::path& physics_dir,
                     const fs::path& emulators_dir, const fs::path& consumers_dir) {
  write_emulator_seeds(emulators_dir);
  write_consumer_seeds(consumers_dir);
  write_decode_seed(decode_dir, "radio_packet", radio_packet(1));
  write_decode_seed(decode_dir, "emulator_realism", realism());
  write_decode_seed(decode_dir, "vision_cameras", cameras());
  write_default_seeds(decode_dir, AllLcmTypes{});
  write_decode_seed(decode_dir, "sim_state", division_b_state());
  write_decode_seed(decode_dir, "sim_commands", commands());
  write_decode_seed(decode_dir, "sim_control_place", placement());
  write_decode_seed(decode_dir, "truth_demand", demand());
  write_decode_seed(decode_dir, "sync_horizon", horizon());
  write_decode_seed(decode_dir, "vision_schedule", schedule());
  write_decode_seed(decode_dir, "referee", referee());

  const auto on = [](PhysicsInput channel, std::uint8_t options = 0) {
    return static_cast<std::uint8_t>(static_cast<std::uint8_t>(channel) | options);
  };
  write(physics_dir, "commands", on(PhysicsInput::SimCommands), encode_or_abort(commands()));
  // What a hostile or broken sender puts in numbers (the handlers must drop these).
  sim_commands_t not_a_number = commands();
  not_a_number.commands[0].vx = std::numeric_limits<double>::quiet_NaN();
  not_a_number.commands[1].kick_speed = std::numeric_limits<double>::infinity();
  not_a_number.commands[2].wheel_speeds[1] = -std::numeric_limits<double>::infinity();
  write(physics_dir, "commands_not_finite", on(PhysicsInput::SimCommands),
        encode_or_abort(not_a_number));
  sim_control_t place_nan = placement();
  place_nan.robots[0].x = std::numeric_limits<double>::quiet_NaN();
  place_nan.ball.linear_velocity[1] = std::numeric_limits<double>::infinity();
  write(physics_dir, "place_not_finite", on(PhysicsInput::SimControl), encode_or_abort(place_nan));
  write(physics_dir, "place", on(PhysicsInput::SimControl), encode_or_abort(placement()));
  sim_control_t setup = placement();
  setup.action = sim_control_t::SETUP;
  write(physics_dir, "setup", on(PhysicsInput::SimControl), encode_or_abort(setup));
  for (std::int8_t action : {sim_control_t::PAUSE, sim_control_t::RESUME, sim_control_t::RESET,
                             sim_control_t::PING, sim_control_t::REQUEST_GEOMETRY}) {
    write(physics_dir, "control_" + std::to_string(action), on(PhysicsInput::SimControl),
          encode_or_abort(control(action)));
  }
  sim_control_t step = control(sim_control_t::STEP);
  step.step_count = 12;
  write(physics_dir, "step", on(PhysicsInput::SimControl), encode_or_abort(step));
  sim_control_t speed = control(sim_control_t::SET_SPEED);
  speed.speed_factor = 2.0;
  write(physics_dir, "speed", on(PhysicsInput::SimControl), encode_or_abort(speed));
  sim_control_t seed = control(sim_control_t::SET_SEED);
  seed.seed = 42;
  write(physics_dir, "seed", on(PhysicsInput::SimControl), encode_or_abort(seed));
  sim_control_t field = control(sim_control_t::SET_FIELD);
  field.field_config =
      read_config_text(fs::path(UBERSIM_FUZZ_CONFIG_DIR) / "fields" / "division_b.cfg");
  write(physics_dir, "field", on(PhysicsInput::SimControl), encode_or_abort(field));
  sim_control_t type = control(sim_control_t::DEFINE_ROBOT_TYPE);
  type.robot_type_name = "fuzz_bot";
  type.robot_type_config = "BASE = omni4_ssl\nMASS = 2.5\n";
  write(physics_dir, "robot_type", on(PhysicsInput::SimControl), encode_or_abort(type));
  sim_control_t dribbling = control(sim_control_t::SET_DRIBBLING);
  dribbling.perfect_dribbling = true;  // dribblers that hold the ball by a joint
  write(physics_dir, "perfect_dribbling", on(PhysicsInput::SimControl), encode_or_abort(dribbling));
  write(physics_dir, "demand", on(PhysicsInput::TruthDemand), encode_or_abort(demand()));
  write(physics_dir, "horizon_sync", on(PhysicsInput::SyncHorizon, kSyncBit),
        encode_or_abort(horizon()));
  write(physics_dir, "schedule_sync", on(PhysicsInput::VisionSchedule, kSyncBit),
        encode_or_abort(schedule()));
  write(physics_dir, "referee_sync", on(PhysicsInput::Referee, kSyncRefereeBit),
        encode_or_abort(referee()));
}

}  // namespace ubersim::fuzz
