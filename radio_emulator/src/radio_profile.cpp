#include "ubersim/radio/radio_profile.hpp"

#include "ubersim/config_paths.hpp"

namespace ubersim::radio {
namespace {

constexpr double kMaxRate = 10000;   // Hz; beyond it a "rate limit" is a typo
constexpr double kMaxDelay = 10;     // s
constexpr double kMaxTimeout = 600;  // s

LinkTiming read_timing(const ConfigFile& config, const std::string& prefix) {
  LinkTiming timing;
  timing.latency = config.real_in(prefix + "LATENCY", 0.0, kMaxDelay);
  timing.latency_jitter = config.real_in(prefix + "LATENCY_JITTER", 0.0, kMaxDelay);
  timing.packet_loss = config.real_in(prefix + "PACKET_LOSS", 0.0, 1.0);
  timing.robot_loss = config.real_in(prefix + "ROBOT_LOSS", 0.0, 1.0);
  return timing;
}

}  // namespace

RadioProfile load_radio_profile(const ConfigFile& config, const std::string& name) {
  RadioProfile p;
  p.name = name;
  p.max_packet_rate = config.real_in("MAX_PACKET_RATE", 0.0, kMaxRate);
  p.command = read_timing(config, "");
  p.command_timeout = config.real_in("COMMAND_TIMEOUT", 0.0, kMaxTimeout);
  p.feedback_rate = config.real_in("FEEDBACK_RATE", 0.0, kMaxRate);
  p.feedback = read_timing(config, "FEEDBACK_");
  p.limits.speed = config.real_in("LIMIT_SPEED", 0.0, 1e3);
  p.limits.angular_speed = config.real_in("LIMIT_ANGULAR_SPEED", 0.0, 1e4);
  p.limits.wheel_speed = config.real_in("LIMIT_WHEEL_SPEED", 0.0, 1e5);
  p.limits.kick_speed = config.real_in("LIMIT_KICK_SPEED", 0.0, 1e3);
  p.limits.dribbler_speed = config.real_in("LIMIT_DRIBBLER_SPEED", 0.0, 1e5);
  const std::int64_t seed = config.integer("SEED");
  if (seed < 0) config.fail("SEED", "expected a seed >= 0, got " + std::to_string(seed));
  p.seed = static_cast<std::uint64_t>(seed);
  config.require_all_used();
  return p;
}

RadioProfile load_radio_profile(const std::string& config_dir, const std::string& name) {
  const auto path = resolve_config(config_dir, "radio", name);
  return load_radio_profile(ConfigFile::load(path), name);
}

}  // namespace ubersim::radio
