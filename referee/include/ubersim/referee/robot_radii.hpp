#pragma once
// The radius of each robot type the referee meets in SIM_STATE (for restart
// placements), read from its robot config (<config-dir>/robots/<type>.cfg).
// The type names come from the bus, so anyone may send any bytes: a name that
// is not a robot type name (valid_robot_type_name: 1..64 letters, digits, '_'
// or '-', never a path), a name with no config, or any new name once the cache
// holds kMaxTypes, gets the fallback radius (the SSL maximum); the first two
// without touching the file system. Each is counted and logged throttled (a
// name with no config once, then it is cached). So the cache stays bounded and
// hostile states cost no file reads beyond the first kMaxTypes names.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

#include "ubersim/logging.hpp"

namespace ubersim::referee {

class RobotRadii {
 public:
  static constexpr double kFallbackRadius = 0.09;  // m, the SSL maximum
  static constexpr std::size_t kMaxTypes = 64;     // names looked up and kept

  explicit RobotRadii(std::filesystem::path config_dir);

  // m; never throws for any name.
  double operator()(const std::string& type);

  std::size_t cached() const { return radii_.size(); }
  std::uint64_t fallbacks() const { return fallbacks_; }  // lookups that got the fallback

 private:
  double fallback(const std::string& key, const std::string& why);

  std::filesystem::path config_dir_;
  std::map<std::string, double> radii_;  // type name -> radius (m), at most kMaxTypes
  std::uint64_t fallbacks_ = 0;
  ThrottledLog log_;
};

}  // namespace ubersim::referee
