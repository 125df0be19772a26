// Fuzz target: the SSL bridge's grSim port (UDP 20011) without the socket:
// decode_datagram as GrsimPort takes it (required fields may be missing),
// every robot command translated into the newest-command book and the radio
// packet it gives, and the replacement translated into SIM_CONTROL requests,
// in a running game (fixture state) and before any SIM_STATE.
#include <grSim_Packet.pb.h>

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "ssl_fixture.hpp"
#include "ubersim/ssl_bridge/datagram_decoding.hpp"
#include "ubersim/ssl_bridge/grsim_command_book.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ubersim::fuzz::quiet_logging();
  ubersim::fuzz::SslFixture::instance();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ubersim::ssl;
  const ubersim::fuzz::SslFixture& fixture = ubersim::fuzz::SslFixture::instance();
  Errors errors;
  grSim_Packet packet;
  if (!decode_datagram(data, size, packet, errors, true).ok) return 0;
  GrsimTranslationSettings settings;
  settings.wheels = fixture.wheels;
  settings.spinner_speed = 1000;
  GrsimCommandBook book(std::chrono::seconds(1));
  const std::chrono::steady_clock::time_point now{};
  const ubersim::Team team =
      packet.commands().isteamyellow() ? ubersim::Team::Yellow : ubersim::Team::Blue;
  for (const grSim_Robot_Command& in : packet.commands().robot_commands()) {
    if (in.id() >= kGrsimMaxRobots) continue;
    const auto id = static_cast<int32_t>(in.id());
    if (auto command = translate_grsim_robot_command(in, settings, book.last(team, id), errors)) {
      book.put(team, *command, now);
    }
  }
  if (book.has_news(team)) ubersim::fuzz::encode_or_abort(book.packet(team, now));
  if (auto later = book.due(team, now + std::chrono::seconds(2), std::chrono::milliseconds(40))) {
    ubersim::fuzz::encode_or_abort(*later);  // the stop
  }
  const std::array<const ubersim::sim_state_t*, 2> states{&fixture.state, nullptr};
  for (const ubersim::sim_state_t* state : states) {
    const SimulatorCommand command = grsim_replacement_command(packet.replacement(), state, errors);
    for (const ubersim::sim_control_t& request :
         translate_simulator_command(command, state, fixture.settings).requests) {
      ubersim::fuzz::encode_or_abort(request);
    }
  }
  return 0;
}
