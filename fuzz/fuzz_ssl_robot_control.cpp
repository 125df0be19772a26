// Fuzz target: the SSL bridge's robot control ports (UDP 10301 blue, 10302
// yellow) without the socket: decode_datagram, translate_robot_control for
// each team (with and without a wheel mapping), and the response the bridge
// sends back, as SslBridge::handle_robot_datagram does.
#include <cstddef>
#include <cstdint>
#include <string>

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
  const ubersim::fuzz::SslFixture& fixture = ubersim::fuzz::SslFixture::instance();
  Errors errors;
  RobotControl control;
  if (decode_datagram(data, size, control, errors).ok) {
    for (const ubersim::Team team : ubersim::kTeams) {
      RobotControlTranslation out = translate_robot_control(control, team, fixture.wheels);
      ubersim::fuzz::encode_or_abort(out.packet);  // what goes on the radio
      errors.insert(errors.end(), out.errors.begin(), out.errors.end());
    }
    (void)translate_robot_control(control, ubersim::Team::Blue, std::nullopt);
  }
  RobotControlResponse response;
  for (const SimulatorError& error : errors) *response.add_errors() = error;
  std::string out;
  response.SerializeToString(&out);
  return 0;
}
