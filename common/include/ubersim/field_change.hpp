#pragma once
// A field changed at run time (SIM_CONTROL SET_FIELD): "KEY = value" lines of
// a field config file that replace those keys of the field in use; the result
// is read by the same reader as config/fields/, so every value is checked. The
// text comes from the network: bounded, and it may not name a BASE file.
#include <string>

#include "ubersim/field_config.hpp"

namespace ubersim {

inline constexpr std::size_t kMaxFieldChangeText = 4 * 1024;  // bytes

// `current` with the keys of `text` replaced. Throws ConfigError (file "field change").
FieldConfig change_field(const FieldConfig& current, const std::string& text);

}  // namespace ubersim
