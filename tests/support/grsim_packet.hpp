#pragma once
// A grSim_Packet as grSim's clients send it: one robot driven forward at a
// speed, every required field set (for tests and benchmarks of the grSim port).
#include <grSim_Packet.pb.h>

#include <cstdint>
#include <string>

namespace ubersim::test {

inline std::string grsim_forward_command(bool yellow, std::uint32_t id, float forward) {
  grSim_Packet packet;
  grSim_Commands* commands = packet.mutable_commands();
  commands->set_timestamp(0);
  commands->set_isteamyellow(yellow);
  grSim_Robot_Command* robot = commands->add_robot_commands();
  robot->set_id(id);
  robot->set_kickspeedx(0);
  robot->set_kickspeedz(0);
  robot->set_veltangent(forward);
  robot->set_velnormal(0);
  robot->set_velangular(0);
  robot->set_spinner(false);
  robot->set_wheelsspeed(false);
  return packet.SerializeAsString();
}

}  // namespace ubersim::test
