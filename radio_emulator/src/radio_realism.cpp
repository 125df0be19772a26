// Run-time realism changes (EMULATOR_REALISM), e.g. an SSL simulation
// protocol realism preset: command latency and per-robot loss of both
// directions change for both teams without a restart.
#include <cmath>
#include <initializer_list>

#include "ubersim/radio/radio_emulator.hpp"

namespace ubersim::radio {

std::string RadioEmulator::apply_realism(const emulator_realism_t& r) {
  for (double v : {r.command_latency, r.command_robot_loss, r.feedback_robot_loss}) {
    if (!std::isfinite(v)) return "a value is not finite";
  }
  if (r.command_robot_loss > 1 || r.feedback_robot_loss > 1) return "a loss above 1";
  if (r.command_latency > 10) return "a latency above 10 s";
  for (TeamLink& link : links_) {  // < 0: unchanged
    if (r.command_latency >= 0) link.profile.command.latency = r.command_latency;
    if (r.command_robot_loss >= 0) link.profile.command.robot_loss = r.command_robot_loss;
    if (r.feedback_robot_loss >= 0) link.profile.feedback.robot_loss = r.feedback_robot_loss;
    link.commands.set_profile(link.profile);
    link.feedback.set_profile(link.profile);
  }
  return "";
}

}  // namespace ubersim::radio
