#pragma once
// A config file's text as the config reader reads it (ConfigFile::load and
// BASE files), for what carries a config's text whole, such as a SIM_CONTROL
// SET_FIELD request.
#include <filesystem>
#include <string>

namespace ubersim {

// Throws ConfigError naming the file: missing, not a regular file, larger than
// 1 MiB (a BASE naming /dev/zero or a FIFO must not read forever), unreadable.
std::string read_config_text(const std::filesystem::path& path);

}  // namespace ubersim
