#pragma once
// The official game controller as a child of the link: started headless in CI
// mode on a free local port, in a folder of its own (its config/ and state
// store there, its output in gc.log), stopped with the link. Its config
// (config/ssl-game-controller.yaml) is written first: no Referee multicast of
// its own (ubersim stamps REFEREE with sim time and the SSL bridge sends it),
// every other port on loopback and free, the halves and breaks of this game.
#include <sys/types.h>

#include <string>

namespace ubersim::gc_link {

struct GcGame {
  double half_duration = 300;      // s
  double half_time_duration = 10;  // s: unattended games use short breaks
  bool division_a = false;
};

// The config file's text (YAML) for this game.
std::string gc_config_yaml(const GcGame& game);

class GcProcess {
 public:
  // Starts `binary` in `folder` (created); throws std::runtime_error with a
  // readable reason when it cannot.
  GcProcess(const std::string& binary, const std::string& folder, const GcGame& game);
  ~GcProcess();
  GcProcess(const GcProcess&) = delete;
  GcProcess& operator=(const GcProcess&) = delete;

  std::string ci_address() const { return "127.0.0.1:" + std::to_string(port_); }
  int port() const { return port_; }
  // Whether it is still running (false once it exited by itself).
  bool running();

 private:
  pid_t pid_ = -1;
  int port_ = 0;
};

// A TCP port on 127.0.0.1 that nothing listens on now.
int free_local_port();

}  // namespace ubersim::gc_link
