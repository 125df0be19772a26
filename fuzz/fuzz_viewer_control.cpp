// Fuzz target: a page's control request (the JSON text of a WebSocket
// message) -> sim_control_t, as the viewer's main loop handles it
// (parse_control_request, then publish on SIM_CONTROL). Nesting bombs,
// huge numbers, odd Unicode: refused with a reason or turned into a request
// that encodes.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.hpp"
#include "ubersim/viewer/json_encoding.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ubersim::fuzz::quiet_logging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto parsed = ubersim::viewer::parse_control_request(text, 7, "viewer");
  if (parsed.request) {
    ubersim::fuzz::encode_or_abort(*parsed.request);
  } else if (parsed.error.empty()) {
    __builtin_trap();  // refused without saying why
  }
  return 0;
}
