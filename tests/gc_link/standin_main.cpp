// ubersim_standin_gc: the CI-mode stand-in for the official game controller
// (standin_gc.hpp) as a program, for the tests that start "the GC" as a binary
// (the batch runner's REFEREE = official PATH). It takes the GC's command line
// as ubersim_gc_link gives it (-timeAcquisitionMode ci -ciAddress HOST:PORT
// -backendOnly), reads the half and break durations from the config file the
// link writes (config/ssl-game-controller.yaml in its working folder), serves
// one CI connection and exits when the link closes it.
#include <cstdio>
#include <fstream>
#include <regex>
#include <string>

#include "standin_gc.hpp"

namespace {

// "half-duration: 6000ms" in the config the link wrote; `fallback` without.
std::int64_t duration_us(const std::string& config, const std::string& key, std::int64_t fallback) {
  std::smatch match;
  if (!std::regex_search(config, match, std::regex("\\b" + key + R"(: ([0-9]+)ms)"))) {
    return fallback;
  }
  return std::stoll(match[1]) * 1000;
}

}  // namespace

int main(int argc, char** argv) {
  int port = -1;
  for (int i = 1; i + 1 < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-ciAddress") {
      const std::string address = argv[i + 1];
      port = std::stoi(address.substr(address.rfind(':') + 1));
    }
  }
  if (port <= 0) {
    std::fprintf(stderr, "ubersim_standin_gc: give -ciAddress HOST:PORT\n");
    return 2;
  }
  std::ifstream file("config/ssl-game-controller.yaml");
  const std::string config((std::istreambuf_iterator<char>(file)),
                           std::istreambuf_iterator<char>());
  standin::StandInTimes times;
  times.half_us = duration_us(config, "half-duration", times.half_us);
  times.break_us = duration_us(config, "half-time-duration", times.break_us);
  standin::StandInGc gc(port, times);
  std::printf("stand-in game controller in CI mode on 127.0.0.1:%d\n", port);
  std::fflush(stdout);
  gc.wait_until_disconnected();
  return 0;
}
