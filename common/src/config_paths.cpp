#include "ubersim/config_paths.hpp"

#include <algorithm>
#include <cstdlib>
#include <vector>

#include "ubersim/config.hpp"

namespace ubersim {

std::filesystem::path default_config_dir() {
  if (const char* env = std::getenv("UBERSIM_CONFIG_DIR"); env && *env) return env;
  return UBERSIM_DEFAULT_CONFIG_DIR;
}

std::filesystem::path resolve_config(const std::filesystem::path& config_dir,
                                     const std::string& kind, const std::string& name) {
  const bool is_path = name.find('/') != std::string::npos ||
                       (name.size() > 4 && name.compare(name.size() - 4, 4, ".cfg") == 0);
  std::filesystem::path path =
      is_path ? std::filesystem::path(name) : config_dir / kind / (name + ".cfg");
  if (std::filesystem::is_regular_file(path)) return path;

  std::vector<std::string> available;
  std::error_code ignored;
  for (const auto& file : std::filesystem::directory_iterator(config_dir / kind, ignored)) {
    if (file.path().extension() == ".cfg") available.push_back(file.path().stem().string());
  }
  std::sort(available.begin(), available.end());
  std::string list;
  for (const auto& a : available) list += (list.empty() ? "" : ", ") + a;
  throw ConfigError(path.string(), 0,
                    "no such " + kind + " config" +
                        (list.empty() ? std::string() : " (available: " + list + ")"));
}

}  // namespace ubersim
