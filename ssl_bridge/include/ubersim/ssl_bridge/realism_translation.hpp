#pragma once
// SimulatorConfig.realism_config -> one emulator_realism_t for the vision and
// radio emulators (EMULATOR_REALISM), which apply it between frames. ER-Force's
// RealismConfigErForce is mapped onto our emulator parameters, field for field
// (simulate_dribbling onto physics'); invalid values are named in one error,
// and a realism config of another simulator is an error.
#include <ssl_simulation_config.pb.h>

#include <optional>
#include <ubersim/emulator_realism_t.hpp>

#include "ubersim/emulator_realism.hpp"
#include "ubersim/ssl_bridge/errors.hpp"

namespace ubersim::ssl {

struct RealismTranslation {
  std::optional<emulator_realism_t> realism;  // request_id and sender left to the caller
  // simulate_dribbling, inverted, for physics (SIM_CONTROL SET_DRIBBLING); unset: unchanged.
  std::optional<bool> perfect_dribbling;
  Errors errors;
};

RealismTranslation translate_realism(const RealismConfig& config);

}  // namespace ubersim::ssl
