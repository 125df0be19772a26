#include "ubersim/cli.hpp"

#include <cstdlib>
#include <map>

#include "ubersim/config_paths.hpp"

namespace ubersim {

std::string default_lcm_url() {
  if (const char* env = std::getenv("LCM_DEFAULT_URL"); env && *env) return env;
  return "udpm://239.255.76.67:7667?ttl=0";
}

std::string with_receive_buffer(const std::string& url) {
  if (url.rfind("udpm://", 0) != 0 || url.find("recv_buf_size") != std::string::npos) return url;
  return url + (url.find('?') == std::string::npos ? "?" : "&") + "recv_buf_size=4194304";
}

ChannelNames CommonOptions::channels() const {
  std::map<std::string, std::string> overrides;
  for (const auto& text : channel_overrides) overrides.insert(ChannelNames::parse_override(text));
  return ChannelNames(channel_prefix, overrides);
}

std::string CommonOptions::config_root() const {
  return config_dir.empty() ? default_config_dir().string() : config_dir;
}

void add_common_options(CLI::App& app, CommonOptions& options) {
  app.add_option("-l,--lcm-url", options.lcm_url, "LCM URL (default: $LCM_DEFAULT_URL or LCM's)")
      ->capture_default_str();
  app.add_option("--channel-prefix", options.channel_prefix,
                 "prefix for every channel name, to run several simulations side by side");
  app.add_option("--channel", options.channel_overrides,
                 "rename one channel, e.g. --channel VISION=CAM_VISION (repeatable)");
  app.add_option("--config-dir", options.config_dir, "folder with fields/, robots/, ... configs")
      ->check(CLI::ExistingDirectory);
  app.add_flag("-v,--verbose", options.verbose, "more log output (-vv for trace)");
  app.add_flag("-q,--quiet", options.quiet, "less log output (-qq for errors only)");
}

}  // namespace ubersim
