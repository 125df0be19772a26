#pragma once
// Config files are named by kind and short name ("fields", "division_b") and
// live at <config-dir>/<kind>/<name>.cfg. Anything that looks like a path
// (has a '/' or ends in ".cfg") is taken as a path as it is.
#include <filesystem>
#include <string>

namespace ubersim {

// The config/ folder this build was made from; --config-dir overrides it.
std::filesystem::path default_config_dir();

// Throws ConfigError when the file does not exist, listing what does.
std::filesystem::path resolve_config(const std::filesystem::path& config_dir,
                                     const std::string& kind, const std::string& name);

}  // namespace ubersim
