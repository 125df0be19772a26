// Fuzz target: the SSL bridge's simulation control port (UDP 10300) without
// the socket: the datagram goes through decode_datagram (size, nesting and
// repeated-field limits, unknown fields dropped) and translate_simulator_command,
// as SslBridge::handle_control_datagram does, against a game in progress and
// once more before physics reported anything.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "ssl_fixture.hpp"
#include "ubersim/ssl_bridge/datagram_decoding.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ubersim::fuzz::quiet_logging();
  ubersim::fuzz::SslFixture::instance();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ubersim::ssl;
  ubersim::fuzz::SslFixture& fixture = ubersim::fuzz::SslFixture::instance();
  Errors errors;
  SimulatorCommand command;
  if (!decode_datagram(data, size, command, errors).ok) return 0;
  SimControlSettings settings = fixture.settings;  // robot specs recorded per input only
  const SimControlTranslation in_game =
      translate_simulator_command(command, &fixture.state, settings);
  // What goes on SIM_CONTROL must encode (counts match the arrays).
  for (const ubersim::sim_control_t& request : in_game.requests)
    ubersim::fuzz::encode_or_abort(request);
  if (in_game.realism) ubersim::fuzz::encode_or_abort(*in_game.realism);
  for (const DefinedRobotType& type : in_game.defined_types) settings.spec_types.record(type);
  settings.current_field = nullptr;
  (void)translate_simulator_command(command, nullptr, settings);
  return 0;
}
