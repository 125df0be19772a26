#pragma once
// A field changed at run time (SIM_CONTROL SET_FIELD): "KEY = value" lines of
// a field config file that replace those keys of the field in use; the result
// is read by the same reader as config/fields/, so every value is checked. The
// text comes from the network: bounded, and it may not name a BASE file.
#include <optional>
#include <string>

#include "ubersim/field_config.hpp"

namespace ubersim {

inline constexpr std::size_t kMaxFieldChangeText = std::size_t{4} * 1024;  // bytes

// `current` with the keys of `text` replaced. Throws ConfigError (file "field change").
FieldConfig change_field(const FieldConfig& current, const std::string& text);

// The radius a field change may also give the ball in play (m): the SSL
// geometry carries it with the field, ubersim keeps it in the ball config.
inline constexpr const char* kBallRadiusKey = "BALL_RADIUS";
inline constexpr double kMinBallRadius = 0.005;  // m
inline constexpr double kMaxBallRadius = 0.2;    // m

struct FieldChange {
  FieldConfig field;
  std::optional<double> ball_radius;  // m, when the text names BALL_RADIUS
};

// As change_field, and BALL_RADIUS (in [kMinBallRadius, kMaxBallRadius]) is
// allowed too. Throws ConfigError.
FieldChange change_field_and_ball(const FieldConfig& current, const std::string& text);

}  // namespace ubersim
