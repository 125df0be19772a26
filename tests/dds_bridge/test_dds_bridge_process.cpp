// The real ubersim_dds_bridge process between real LCM multicast and real
// Cyclone DDS participants in this test process (ISOLATED: its own network
// namespace with only lo; DDS domain kDomain of its own).
#include <gtest/gtest.h>
#include <signal.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <regex>
#include <ubersim/sim_control_t.hpp>

#include "child_process.hpp"
#include "dds_test_support.hpp"
#include "sample_messages.hpp"
#include "ubersim/common_options.hpp"
#include "ubersim/dds_bridge/convert.hpp"
#include "ubersim/dds_bridge/echo_filter.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/topics.hpp"

namespace dds = ubersim::dds;
using dds::TopicUse;
using ubersim::ChannelNames;
using ubersim::MessageBus;
using ubersim::Team;

namespace {

constexpr dds_domainid_t kDomain = 42;
constexpr double kTimeout = 15;  // s; discovery and delivery take well under 1 s unloaded

std::string write_config(const std::string& name, const std::string& text) {
  std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

// The count after "<what>: ... <field> N" in the bridge's exit summary, -1 if absent.
long summary_count(const std::string& log, const std::string& route, const std::string& field) {
  const std::regex line(route + ": ([^\n]*)");
  std::smatch match;
  if (!std::regex_search(log, match, line)) return -1;
  const std::string rest = match[1];
  const std::regex number(field + " ([0-9]+)");
  std::smatch count;
  if (!std::regex_search(rest, count, number)) return -1;
  return std::stol(count[1]);
}

class DdsBridgeProcess : public ::testing::Test {
 protected:
  void start_bridge(const std::string& config = "default") {
    std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    for (char& c : test)
      if (c == '/') c = '_';  // parameterised tests are named "Name/0"
    const std::string log = ::testing::TempDir() + "dds_bridge_" + test + ".log";
    bridge_ = std::make_unique<ubersim::test::ChildProcess>(
        std::vector<std::string>{UBERSIM_DDS_BRIDGE_EXE, "--domain", std::to_string(kDomain),
                                 "--config", config, "-v"},
        log);
  }
  // SIGTERM; the exit status.
  int stop_bridge(int signal_number = SIGTERM) { return bridge_->stop(10, signal_number); }
  std::string bridge_log() const { return bridge_->log(); }

  // Publishes vision frames on LCM until one arrives on `reader`; returns its frame number.
  std::int64_t warm_up_vision(dds_entity_t reader) {
    std::int64_t number = 1000;
    std::int64_t received = -1;
    const bool ok = dds_test::pump_until(
        bus_, [&] { return received >= 0; }, kTimeout,
        [&] {
          ubersim::publish(bus_, channels_, ubersim::topics::kVision,
                           dds_test::vision_frame(++number));
          std::this_thread::sleep_for(std::chrono::milliseconds(20));
          dds_test::take_each<dds::DdsVisionFrame>(
              reader, [&](const dds::DdsVisionFrame& f) { received = f.frame_number; });
        });
    EXPECT_TRUE(ok) << "no vision frame crossed; bridge log:\n" << bridge_log();
    return received;
  }

  dds_test::DdsSide dds_{kDomain};
  ChannelNames channels_;
  MessageBus bus_{ubersim::with_receive_buffer(ubersim::default_lcm_url())};
  std::unique_ptr<ubersim::test::ChildProcess> bridge_;
};

// A radio packet written field by field in the IDL's C form (not through the
// bridge's own conversion), with storage that lives as long as this object.
struct DdsRadioSample {
  std::array<dds::DdsRobotCommand, 2> commands{};
  std::array<double, 4> wheels{11.5, -12.25, 13.0, -14.75};
  dds::DdsRadioPacket packet{};

  DdsRadioSample(std::int8_t team, std::int64_t sequence) {
    packet.team = team;
    packet.sequence_number = sequence;
    packet.t_sent = 3.0 + 0.001 * static_cast<double>(sequence);
    auto& a = commands[0];
    a.robot_id = 2;
    a.mode = ubersim_msgs_msg_RobotCommand_Constants_MODE_LOCAL_VELOCITY;
    a.vx = 1.25;
    a.vy = -0.5;
    a.omega = 3.5;
    a.kick_speed = 6.5;
    a.chip_speed = 0;
    a.chip_angle = 0;
    a.dribbler_speed = 250;
    auto& b = commands[1];
    b.robot_id = 7;
    b.mode = ubersim_msgs_msg_RobotCommand_Constants_MODE_WHEEL_SPEEDS;
    b.wheel_speeds._buffer = wheels.data();
    b.wheel_speeds._length = b.wheel_speeds._maximum = 4;
    b.wheel_speeds._release = false;
    b.chip_speed = 2.5;
    b.chip_angle = 0.6;
    b.dribbler_speed = -100;
    packet.commands._buffer = commands.data();
    packet.commands._length = packet.commands._maximum = 2;
    packet.commands._release = false;
  }
};

void expect_same_command(const dds::DdsRobotCommand& d, const ubersim::robot_command_t& l) {
  EXPECT_EQ(l.robot_id, d.robot_id);
  EXPECT_EQ(l.mode, d.mode);
  EXPECT_EQ(l.vx, d.vx);
  EXPECT_EQ(l.vy, d.vy);
  EXPECT_EQ(l.omega, d.omega);
  ASSERT_EQ(l.num_wheels, static_cast<std::int32_t>(d.wheel_speeds._length));
  ASSERT_EQ(l.wheel_speeds.size(), d.wheel_speeds._length);
  for (std::size_t w = 0; w < l.wheel_speeds.size(); ++w)
    EXPECT_EQ(l.wheel_speeds[w], d.wheel_speeds._buffer[w]);
  EXPECT_EQ(l.kick_speed, d.kick_speed);
  EXPECT_EQ(l.chip_speed, d.chip_speed);
  EXPECT_EQ(l.chip_angle, d.chip_angle);
  EXPECT_EQ(l.dribbler_speed, d.dribbler_speed);
}

}  // namespace

TEST_F(DdsBridgeProcess, LcmVisionFrameAppearsOnDdsWithIdenticalValues) {
  start_bridge();
  const dds_entity_t topic =
      dds_test::make_topic<dds::DdsVisionFrame>(dds_.participant(), "rt/ubersim/vision");
  const dds_entity_t reader = dds_test::make_reader(dds_.participant(), topic, TopicUse::Stream);
  ASSERT_TRUE(dds_test::wait_for_writers(reader, kTimeout)) << bridge_log();
  warm_up_vision(reader);

  const ubersim::vision_frame_t sent = dds_test::vision_frame(7, 3, 5);
  ubersim::publish(bus_, channels_, ubersim::topics::kVision, sent);
  int seen = 0;
  ASSERT_TRUE(dds_test::pump_until(
      bus_, [&] { return seen > 0; }, kTimeout,
      [&] {
        dds_test::take_each<dds::DdsVisionFrame>(reader, [&](const dds::DdsVisionFrame& d) {
          if (d.frame_number != sent.frame_number) return;
          ++seen;
          EXPECT_EQ(d.camera_id, sent.camera_id);
          EXPECT_EQ(d.t_capture, sent.t_capture);
          EXPECT_EQ(d.t_sent, sent.t_sent);
          ASSERT_EQ(d.balls._length, 3u);
          for (std::size_t i = 0; i < 3; ++i) {
            EXPECT_EQ(d.balls._buffer[i].confidence, sent.balls[i].confidence);
            EXPECT_EQ(d.balls._buffer[i].x, sent.balls[i].x);
            EXPECT_EQ(d.balls._buffer[i].y, sent.balls[i].y);
            EXPECT_EQ(d.balls._buffer[i].pixel_x, sent.balls[i].pixel_x);
            EXPECT_EQ(d.balls._buffer[i].pixel_y, sent.balls[i].pixel_y);
          }
          for (const auto& [dds_robots, lcm_robots] :
               {std::pair{&d.robots_yellow, &sent.robots_yellow},
                std::pair{&d.robots_blue, &sent.robots_blue}}) {
            ASSERT_EQ(dds_robots->_length, lcm_robots->size());
            for (std::size_t i = 0; i < lcm_robots->size(); ++i) {
              const auto& r = dds_robots->_buffer[i];
              const auto& l = (*lcm_robots)[i];
              EXPECT_EQ(r.robot_id, l.robot_id);
              EXPECT_EQ(r.confidence, l.confidence);
              EXPECT_EQ(r.x, l.x);
              EXPECT_EQ(r.y, l.y);
              EXPECT_EQ(r.orientation, l.orientation);
              EXPECT_EQ(r.pixel_x, l.pixel_x);
              EXPECT_EQ(r.pixel_y, l.pixel_y);
            }
          }
        });
      }))
      << bridge_log();
  EXPECT_EQ(seen, 1);
  EXPECT_EQ(stop_bridge(), 0);
}

TEST_F(DdsBridgeProcess, DdsRadioPacketAppearsOnRadioTeamWithIdenticalValues) {
  start_bridge();
  std::vector<ubersim::radio_packet_t> yellow;
  std::vector<ubersim::radio_packet_t> blue;
  ubersim::subscribe(bus_, channels_, ubersim::topics::kRadio.of(Team::Yellow),
                     [&](const ubersim::radio_packet_t& p) { yellow.push_back(p); });
  ubersim::subscribe(bus_, channels_, ubersim::topics::kRadio.of(Team::Blue),
                     [&](const ubersim::radio_packet_t& p) { blue.push_back(p); });

  for (const Team team : ubersim::kTeams) {
    const std::string topic_name =
        team == Team::Yellow ? "rt/ubersim/radio_yellow" : "rt/ubersim/radio_blue";
    const dds_entity_t topic =
        dds_test::make_topic<dds::DdsRadioPacket>(dds_.participant(), topic_name);
    const dds_entity_t writer = dds_test::make_writer(dds_.participant(), topic, TopicUse::Command);
    ASSERT_TRUE(dds_test::wait_for_readers(writer, kTimeout)) << bridge_log();
    const DdsRadioSample sample(static_cast<std::int8_t>(team), 40 + static_cast<int>(team));
    ASSERT_EQ(dds_write(writer, &sample.packet), DDS_RETCODE_OK);
    auto& received = team == Team::Yellow ? yellow : blue;
    ASSERT_TRUE(dds_test::pump_until(
        bus_, [&] { return !received.empty(); }, kTimeout))
        << bridge_log();
    const ubersim::radio_packet_t& p = received.front();
    EXPECT_EQ(p.team, sample.packet.team);
    EXPECT_EQ(p.sequence, sample.packet.sequence_number);
    EXPECT_EQ(p.t_sent, sample.packet.t_sent);
    ASSERT_EQ(p.num_commands, 2);
    ASSERT_EQ(p.commands.size(), 2u);
    expect_same_command(sample.commands[0], p.commands[0]);
    expect_same_command(sample.commands[1], p.commands[1]);
  }
  dds_test::pump_for(bus_, 0.3);
  EXPECT_EQ(yellow.size(), 1u);  // each packet on its own team's channel only
  EXPECT_EQ(blue.size(), 1u);
  EXPECT_EQ(stop_bridge(), 0);
}

// Nothing comes back to the side it came from: an LCM frame is one DDS sample
// and one LCM message (ours); a DDS packet is one LCM message and one DDS
// sample (ours). Run with the shipped config and with both directions open on
// the same channels, where only the loop guards stop an echo.
class DdsBridgeEcho : public DdsBridgeProcess, public ::testing::WithParamInterface<bool> {};

TEST_P(DdsBridgeEcho, NothingEchoesBack) {
  const bool both_ways = GetParam();
  start_bridge(both_ways ? write_config("dds_both.cfg",
                                        "TOPIC_PREFIX = rt/ubersim/\n"
                                        "VISION = both\n"
                                        "RADIO_YELLOW = both\n")
                         : "default");
  int lcm_vision = 0;
  int lcm_radio = 0;
  ubersim::subscribe(bus_, channels_, ubersim::topics::kVision,
                     [&](const ubersim::vision_frame_t&) { ++lcm_vision; });
  ubersim::subscribe(bus_, channels_, ubersim::topics::kRadio.of(Team::Yellow),
                     [&](const ubersim::radio_packet_t&) { ++lcm_radio; });
  // Participant A writes radio; B reads both topics, as a separate program would.
  const dds_entity_t a = dds_.new_participant();
  const dds_entity_t b = dds_.new_participant();
  const dds_entity_t vision_reader = dds_test::make_reader(
      b, dds_test::make_topic<dds::DdsVisionFrame>(b, "rt/ubersim/vision"), TopicUse::Stream);
  const dds_entity_t radio_reader = dds_test::make_reader(
      b, dds_test::make_topic<dds::DdsRadioPacket>(b, "rt/ubersim/radio_yellow"),
      TopicUse::Command);
  const dds_entity_t radio_writer = dds_test::make_writer(
      a, dds_test::make_topic<dds::DdsRadioPacket>(a, "rt/ubersim/radio_yellow"),
      TopicUse::Command);
  ASSERT_TRUE(dds_test::wait_for_writers(vision_reader, kTimeout)) << bridge_log();
  ASSERT_TRUE(dds_test::wait_for_readers(radio_writer, kTimeout, 2))
      << bridge_log();  // the bridge's reader and B's
  warm_up_vision(vision_reader);
  dds_test::pump_for(bus_, 0.3, [&] {
    dds_test::take_each<dds::DdsVisionFrame>(vision_reader, [](const dds::DdsVisionFrame&) {});
  });
  lcm_vision = 0;

  int dds_vision = 0;
  int dds_radio = 0;
  const auto take = [&] {
    dds_vision +=
        dds_test::take_each<dds::DdsVisionFrame>(vision_reader, [](const dds::DdsVisionFrame&) {});
    dds_radio +=
        dds_test::take_each<dds::DdsRadioPacket>(radio_reader, [](const dds::DdsRadioPacket&) {});
  };
  ubersim::publish(bus_, channels_, ubersim::topics::kVision, dds_test::vision_frame(1));
  const DdsRadioSample sample(0, 1);
  ASSERT_EQ(dds_write(radio_writer, &sample.packet), DDS_RETCODE_OK);
  ASSERT_TRUE(dds_test::pump_until(
      bus_, [&] { return dds_vision >= 1 && lcm_radio >= 1 && dds_radio >= 1; }, kTimeout, take))
      << bridge_log();
  dds_test::pump_for(bus_, 1.0, take);  // time for an echo to show
  EXPECT_EQ(lcm_vision, 1);             // ours only
  EXPECT_EQ(dds_vision, 1);
  EXPECT_EQ(lcm_radio, 1);
  EXPECT_EQ(dds_radio, 1);  // A's only

  ASSERT_EQ(stop_bridge(), 0);
  const std::string log = bridge_log();
  if (both_ways) {
    // The loop guards did the work: the bridge heard its own radio packet on
    // LCM and did not send it back; its own vision sample never reached it.
    EXPECT_EQ(summary_count(log, "RADIO_YELLOW lcm_to_dds", "echoes"), 1) << log;
    EXPECT_EQ(summary_count(log, "RADIO_YELLOW lcm_to_dds", "forwarded"), 0) << log;
    EXPECT_EQ(summary_count(log, "VISION dds_to_lcm", "received"), 0) << log;
  }
}

INSTANTIATE_TEST_SUITE_P(ShippedConfigAndBothWays, DdsBridgeEcho, ::testing::Values(false, true));

TEST_F(DdsBridgeProcess, LateJoiningDdsSubscriberReceivesTheFieldGeometry) {
  // Stand in for physics: answer the bridge's geometry request on LCM.
  bool requested = false;
  ubersim::subscribe(bus_, channels_, ubersim::topics::kSimControl,
                     [&](const ubersim::sim_control_t& c) {
                       if (c.action == ubersim::sim_control_t::REQUEST_GEOMETRY) requested = true;
                     });
  start_bridge();
  ASSERT_TRUE(dds_test::pump_until(
      bus_, [&] { return requested; }, kTimeout))
      << "the bridge did not ask for the geometry\n"
      << bridge_log();
  const ubersim::field_geometry_t field = dds_test::field_geometry(0.25);
  const ubersim::vision_geometry_t vision = dds_test::vision_geometry(0.5);
  ubersim::publish(bus_, channels_, ubersim::topics::kSimGeometry, field);
  ubersim::publish(bus_, channels_, ubersim::topics::kVisionGeometry, vision);

  // An early subscriber confirms the bridge has written both.
  const dds_entity_t early = dds_.new_participant();
  const dds_entity_t early_field = dds_test::make_reader(
      early, dds_test::make_topic<dds::DdsFieldGeometry>(early, "rt/ubersim/sim_geometry"),
      TopicUse::Geometry);
  const dds_entity_t early_vision = dds_test::make_reader(
      early, dds_test::make_topic<dds::DdsVisionGeometry>(early, "rt/ubersim/vision_geometry"),
      TopicUse::Geometry);
  int early_seen = 0;
  ASSERT_TRUE(dds_test::pump_until(
      bus_, [&] { return early_seen == 2; }, kTimeout,
      [&] {
        early_seen += dds_test::take_each<dds::DdsFieldGeometry>(early_field, [](const auto&) {});
        early_seen += dds_test::take_each<dds::DdsVisionGeometry>(early_vision, [](const auto&) {});
      }))
      << bridge_log();

  // Nothing is published any more; a subscriber joining now still gets both.
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const dds_entity_t late = dds_.new_participant();
  const dds_entity_t late_field = dds_test::make_reader(
      late, dds_test::make_topic<dds::DdsFieldGeometry>(late, "rt/ubersim/sim_geometry"),
      TopicUse::Geometry);
  const dds_entity_t late_vision = dds_test::make_reader(
      late, dds_test::make_topic<dds::DdsVisionGeometry>(late, "rt/ubersim/vision_geometry"),
      TopicUse::Geometry);
  std::vector<ubersim::field_geometry_t> fields;
  std::vector<ubersim::vision_geometry_t> visions;
  ASSERT_TRUE(dds_test::pump_until(
      bus_, [&] { return !fields.empty() && !visions.empty(); }, kTimeout,
      [&] {
        dds_test::take_each<dds::DdsFieldGeometry>(late_field, [&](const dds::DdsFieldGeometry& d) {
          fields.push_back(dds::from_dds(d));
        });
        dds_test::take_each<dds::DdsVisionGeometry>(
            late_vision,
            [&](const dds::DdsVisionGeometry& d) { visions.push_back(dds::from_dds(d)); });
      }))
      << bridge_log();
  ASSERT_EQ(fields.size(), 1u);
  EXPECT_EQ(fields[0].name, field.name);
  EXPECT_EQ(fields[0].field_length, field.field_length);
  EXPECT_EQ(fields[0].penalty_mark_distance, field.penalty_mark_distance);
  EXPECT_EQ(dds::lcm_bytes(fields[0]), dds::lcm_bytes(field));  // every field identical
  ASSERT_EQ(visions.size(), 1u);
  EXPECT_EQ(dds::lcm_bytes(visions[0]), dds::lcm_bytes(vision));
  EXPECT_EQ(stop_bridge(), 0);
}

TEST_F(DdsBridgeProcess, BadSamplesAreDroppedAndCounted) {
  start_bridge();
  std::vector<ubersim::radio_packet_t> radio;
  std::vector<ubersim::sim_control_t> control;
  ubersim::subscribe(bus_, channels_, ubersim::topics::kRadio.of(Team::Yellow),
                     [&](const ubersim::radio_packet_t& p) { radio.push_back(p); });
  ubersim::subscribe(bus_, channels_, ubersim::topics::kSimControl,
                     [&](const ubersim::sim_control_t& c) {
                       if (c.sender == "dds test") control.push_back(c);
                     });
  const dds_entity_t radio_writer = dds_test::make_writer(
      dds_.participant(),
      dds_test::make_topic<dds::DdsRadioPacket>(dds_.participant(), "rt/ubersim/radio_yellow"),
      TopicUse::Command);
  const dds_entity_t control_writer = dds_test::make_writer(
      dds_.participant(),
      dds_test::make_topic<dds::DdsSimControl>(dds_.participant(), "rt/ubersim/sim_control"),
      TopicUse::Command);
  ASSERT_TRUE(dds_test::wait_for_readers(radio_writer, kTimeout)) << bridge_log();
  ASSERT_TRUE(dds_test::wait_for_readers(control_writer, kTimeout)) << bridge_log();

  DdsRadioSample nan_entry(0, 1);  // robot 2 NaN, robot 7 fine: robot 7 goes on
  nan_entry.commands[0].vx = std::numeric_limits<double>::quiet_NaN();
  DdsRadioSample absurd(0, 2);  // 150 m/s and a negative kick: nothing left
  absurd.commands[0].vx = 150;
  absurd.commands[1].kick_speed = -3;
  DdsRadioSample wrong_team(1, 3);  // blue's packet on yellow's topic
  const DdsRadioSample good(0, 4);
  for (const DdsRadioSample* s :
       std::initializer_list<const DdsRadioSample*>{&nan_entry, &absurd, &wrong_team, &good})
    ASSERT_EQ(dds_write(radio_writer, &s->packet), DDS_RETCODE_OK);

  auto bad_control = dds::to_dds(dds_test::sim_control(1));
  bad_control.get().speed_factor = std::numeric_limits<double>::infinity();
  const auto good_control = dds::to_dds(dds_test::sim_control(2));
  ASSERT_EQ(dds_write(control_writer, &bad_control.get()), DDS_RETCODE_OK);
  ASSERT_EQ(dds_write(control_writer, &good_control.get()), DDS_RETCODE_OK);

  // Reliable and in order: once the good ones are here, the bad ones are not coming.
  ASSERT_TRUE(dds_test::pump_until(
      bus_,
      [&] {
        return !radio.empty() && radio.back().sequence == 4 && !control.empty() &&
               control.back().request_id == 2;
      },
      kTimeout))
      << bridge_log();
  dds_test::pump_for(bus_, 0.3);
  ASSERT_EQ(radio.size(), 2u);
  EXPECT_EQ(radio[0].sequence, 1);
  ASSERT_EQ(radio[0].num_commands, 1);
  EXPECT_EQ(radio[0].commands[0].robot_id, 7);
  EXPECT_EQ(radio[1].sequence, 4);
  EXPECT_EQ(radio[1].num_commands, 2);
  ASSERT_EQ(control.size(), 1u);
  EXPECT_EQ(control[0].request_id, 2);
  EXPECT_TRUE(bridge_->running()) << "the bridge must survive bad samples";

  ASSERT_EQ(stop_bridge(), 0);
  const std::string log = bridge_log();
  EXPECT_EQ(summary_count(log, "RADIO_YELLOW dds_to_lcm", "received"), 4) << log;
  EXPECT_EQ(summary_count(log, "RADIO_YELLOW dds_to_lcm", "forwarded"), 2) << log;
  EXPECT_EQ(summary_count(log, "RADIO_YELLOW dds_to_lcm", "dropped"), 2) << log;
  EXPECT_EQ(summary_count(log, "RADIO_YELLOW dds_to_lcm", "entries removed"), 1) << log;
  EXPECT_EQ(summary_count(log, "RADIO_YELLOW dds_to_lcm", "NaN/Inf"), 1) << log;
  EXPECT_EQ(summary_count(log, "RADIO_YELLOW dds_to_lcm", "absurd value"), 2) << log;
  EXPECT_EQ(summary_count(log, "RADIO_YELLOW dds_to_lcm", "team does not match channel"), 1) << log;
  EXPECT_EQ(summary_count(log, "SIM_CONTROL dds_to_lcm", "received"), 2) << log;
  EXPECT_EQ(summary_count(log, "SIM_CONTROL dds_to_lcm", "dropped"), 1) << log;
  EXPECT_EQ(summary_count(log, "SIM_CONTROL dds_to_lcm", "NaN/Inf"), 1) << log;
  // And the bad input was reported while it happened, not only at exit.
  const auto warned = log.find("removed NaN/Inf (robot 2)");
  ASSERT_NE(warned, std::string::npos) << log;
  EXPECT_LT(warned, log.find("RADIO_YELLOW dds_to_lcm:")) << log;
}

TEST_F(DdsBridgeProcess, SurvivesDdsPeersComingAndGoing) {
  start_bridge();
  std::vector<ubersim::radio_packet_t> radio;
  ubersim::subscribe(bus_, channels_, ubersim::topics::kRadio.of(Team::Yellow),
                     [&](const ubersim::radio_packet_t& p) { radio.push_back(p); });
  for (int round = 1; round <= 3; ++round) {
    // A control program starts, sends, and goes away (its participant deleted).
    const dds_entity_t program = dds_.new_participant();
    const dds_entity_t writer = dds_test::make_writer(
        program, dds_test::make_topic<dds::DdsRadioPacket>(program, "rt/ubersim/radio_yellow"),
        TopicUse::Command);
    // A viewer comes and goes on the vision topic at the same time.
    const dds_entity_t viewer = dds_.new_participant();
    const dds_entity_t vision = dds_test::make_reader(
        viewer, dds_test::make_topic<dds::DdsVisionFrame>(viewer, "rt/ubersim/vision"),
        TopicUse::Stream);
    ASSERT_TRUE(dds_test::wait_for_readers(writer, kTimeout)) << bridge_log();
    ASSERT_TRUE(dds_test::wait_for_writers(vision, kTimeout)) << bridge_log();
    warm_up_vision(vision);
    const DdsRadioSample sample(0, round);
    ASSERT_EQ(dds_write(writer, &sample.packet), DDS_RETCODE_OK);
    ASSERT_TRUE(dds_test::pump_until(
        bus_, [&] { return !radio.empty() && radio.back().sequence == round; }, kTimeout))
        << "round " << round << "\n"
        << bridge_log();
    ASSERT_EQ(dds_delete(viewer), DDS_RETCODE_OK);
    ASSERT_EQ(dds_delete(program), DDS_RETCODE_OK);
    dds_test::pump_for(bus_, 0.2, [&] {
      ubersim::publish(bus_, channels_, ubersim::topics::kVision,
                       dds_test::vision_frame(round));  // nobody listens
    });
    ASSERT_TRUE(bridge_->running()) << bridge_log();
  }
  EXPECT_EQ(radio.size(), 3u);
  EXPECT_EQ(stop_bridge(), 0);
}

TEST_F(DdsBridgeProcess, SigintExitsZero) {
  start_bridge();
  const dds_entity_t reader = dds_test::make_reader(
      dds_.participant(),
      dds_test::make_topic<dds::DdsSimState>(dds_.participant(), "rt/ubersim/sim_state"),
      TopicUse::Stream);
  ASSERT_TRUE(dds_test::wait_for_writers(reader, kTimeout)) << bridge_log();
  EXPECT_EQ(stop_bridge(SIGINT), 0) << bridge_log();
}

TEST_F(DdsBridgeProcess, BadConfigExitsTwoNamingFileAndLine) {
  const std::string path = write_config("dds_bad.cfg",
                                        "TOPIC_PREFIX = rt/ubersim/\n"
                                        "VISION = sideways\n");
  start_bridge(path);
  EXPECT_EQ(bridge_->wait(10), 2);
  EXPECT_NE(bridge_log().find("dds_bad.cfg:2"), std::string::npos) << bridge_log();
}

TEST_F(DdsBridgeProcess, DomainOutOfRangeIsRefused) {
  ubersim::test::ChildProcess bridge({UBERSIM_DDS_BRIDGE_EXE, "--domain", "300"},
                                     ::testing::TempDir() + "dds_bad_domain.log");
  const int status = bridge.wait(10);
  EXPECT_NE(status, 0);
  EXPECT_NE(status, -1);  // refused at once, not hung
  EXPECT_NE(bridge.log().find("domain"), std::string::npos) << bridge.log();
}
