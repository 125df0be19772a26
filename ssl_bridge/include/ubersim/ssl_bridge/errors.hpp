#pragma once
// Error codes the bridge answers with (SimulatorError.code): stable strings a
// team's software can match on.
#include <ssl_simulation_error.pb.h>

#include <string>
#include <vector>

namespace ubersim::ssl {

inline constexpr const char* kErrorMalformed = "UBERSIM_MALFORMED";  // does not decode
inline constexpr const char* kErrorUnknownFields =
    "UBERSIM_UNKNOWN_FIELDS";  // fields we do not know
inline constexpr const char* kErrorTooLarge =
    "UBERSIM_TOO_LARGE";  // over a size limit (datagram, repeated field)
inline constexpr const char* kErrorUnsupported = "UBERSIM_UNSUPPORTED";  // a feature we lack
inline constexpr const char* kErrorInvalid = "UBERSIM_INVALID_VALUE";    // NaN, negative speed ...
inline constexpr const char* kErrorUnknownRobot = "UBERSIM_UNKNOWN_ROBOT";  // not on the field
inline constexpr const char* kErrorPhysics = "UBERSIM_PHYSICS_REFUSED";     // physics said no
inline constexpr const char* kErrorBusy = "UBERSIM_BUSY";           // too many commands waiting
inline constexpr const char* kErrorNoAnswer = "UBERSIM_NO_ANSWER";  // physics silent

using Errors = std::vector<SimulatorError>;

inline void add_error(Errors& errors, const char* code, const std::string& message) {
  SimulatorError error;
  error.set_code(code);
  error.set_message(message);
  errors.push_back(std::move(error));
}

}  // namespace ubersim::ssl
