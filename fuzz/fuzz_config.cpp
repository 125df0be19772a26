// Fuzz target: the config reader (ConfigFile) and the typed loaders that read
// robot, field and scenario files out of it, and the same reader where its
// text comes from the bus (field changes, robot types defined at run time). The contract under
// test: any text either loads or throws ConfigError (file:line: what was expected); any other
// exception, a crash, a hang or a large allocation is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.hpp"
#include "ubersim/config.hpp"
#include "ubersim/field_change.hpp"
#include "ubersim/field_config.hpp"
#include "ubersim/robot_config.hpp"
#include "ubersim/robot_type_definition.hpp"
#include "ubersim/scenario_config.hpp"

namespace {

const ubersim::FieldConfig& division_b() {
  static const ubersim::FieldConfig field =
      ubersim::load_field_config(UBERSIM_FUZZ_CONFIG_DIR, "division_b");
  return field;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ubersim::fuzz::quiet_logging();
  division_b();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  // Named as a file beside the shipped robots, so BASE = omni4_ssl.cfg (as in
  // the seeds) resolves as it would for a user's file.
  const std::string name = std::string(UBERSIM_FUZZ_CONFIG_DIR) + "/robots/fuzz_input.cfg";
  try {
    const ubersim::ConfigFile config = ubersim::ConfigFile::parse(text, name);
    for (const std::string& key : config.keys()) (void)config.where(key);
    try {
      (void)ubersim::load_robot_config(config, "fuzz_input");
    } catch (const ubersim::ConfigError&) {
    }
    try {
      (void)ubersim::load_field_config(config, "fuzz_input");
    } catch (const ubersim::ConfigError&) {
    }
    try {
      (void)ubersim::load_scenario_config(config, "fuzz_input");
    } catch (const ubersim::ConfigError&) {
    }
  } catch (const ubersim::ConfigError&) {
  }
  // The same text as a field change (SIM_CONTROL SET_FIELD from the bus).
  try {
    (void)ubersim::change_field(division_b(), text);
  } catch (const ubersim::ConfigError&) {
  }
  // The same text as a robot type defined at run time (SIM_CONTROL from the
  // bus, SSL robot specs): it must never get to read a file through BASE.
  try {
    (void)ubersim::parse_robot_type_definition("fuzz_type", text);
  } catch (const ubersim::ConfigError& error) {
    // "fuzz_type:LINE: BASE file '...'" is the reader opening the file; the
    // same words elsewhere are the input's own text quoted in another error.
    const std::string what = error.what();
    const std::size_t separator = what.find(": ");
    if (separator != std::string::npos && what.compare(separator, 13, ": BASE file '") == 0) {
      __builtin_trap();
    }
  }
  return 0;
}
