#include "demo_team.hpp"

#include <ubersim/team_t.hpp>
#include <utility>

#include "ubersim/topics.hpp"

namespace demo {
namespace {

// In play mode the referee decides what the team may do.
std::vector<ubersim::robot_command_t> play_by_the_rules(GameMode mode, const WorldModel& world,
                                                        const TeamSetup& team) {
  switch (mode) {
    case GameMode::Halt:
    case GameMode::Hold:
      return halt(world);
    case GameMode::Stop:
      return keep_away(world, team);
    case GameMode::Play:
      break;
  }
  return play(world, team);
}

}  // namespace

DemoTeam::DemoTeam(const DemoTeamOptions& options, ubersim::Team own, ubersim::MessageBus& bus,
                   const ubersim::ChannelNames& channels)
    : options_(options),
      team_(options.team),
      yellow_(own == ubersim::Team::Yellow),
      team_code_(yellow_ ? ubersim::team_t::YELLOW : ubersim::team_t::BLUE),
      bus_(bus),
      radio_channel_(ubersim::channel_name(channels, ubersim::topics::kRadio.of(own))),
      world_(yellow_),
      referee_(yellow_) {}

void DemoTeam::on_geometry(const ubersim::vision_geometry_t& geometry) {
  team_.field_length = geometry.field.field_length;
  team_.field_width = geometry.field.field_width;
}

void DemoTeam::on_frame(const ubersim::vision_frame_t& frame) {
  if (frame.t_capture + 1.0 < world_.now()) {  // the simulation was reset
    world_ = WorldModel(yellow_);
    last_sent_ = -1e9;
  }
  world_.update(frame);
  referee_.advance_to(frame.t_sent);
  team_.keeper_id = referee_.goalkeeper();
  if (world_.now() - last_sent_ < 1.0 / options_.rate - 1e-9) {
    if (options_.sync) send({}, frame.t_capture);  // nothing to send: the answer says so
    return;
  }
  last_sent_ = world_.now();
  world_.forget_older_than(1.0);
  send(commands(), options_.sync ? frame.t_capture : world_.now());
}

std::vector<ubersim::robot_command_t> DemoTeam::commands() const {
  if (options_.mode == "positions") return hold_positions(world_, team_);
  if (options_.mode == "figure8") {
    return figure_eights(world_, team_, options_.figure8_speed, options_.figure8_size);
  }
  return play_by_the_rules(referee_.mode(), world_, team_);
}

void DemoTeam::send(std::vector<ubersim::robot_command_t> commands, double t_sent) {
  ubersim::radio_packet_t packet{};
  packet.team = team_code_;
  packet.sequence = sequence_++;
  packet.t_sent = t_sent;
  packet.commands = std::move(commands);
  packet.num_commands = static_cast<int32_t>(packet.commands.size());
  bus_.publish(radio_channel_, packet);
}

}  // namespace demo
