#pragma once
// A CI-mode stand-in for the official game controller, for the link test only
// (CI machines cannot build the GC; test_official_gc runs the real one). It
// listens on a free port of 127.0.0.1, speaks the CI port's framing, and
// answers the way the GC does: one CiOutput per processed change and one per
// tick (a CiInput with a timestamp), the status message of SetStatusMessage
// in its Referee, the timestamp as its clock. Its game is a small one: STOP
// held 1 s -> PREPARE_KICKOFF of the first kick-off team, 1 s later
// NORMAL_START (and the first half); a POSSIBLE_GOAL halts and scores.
#include <ssl_gc_ci.pb.h>

#include <atomic>
#include <cstdint>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

namespace standin {

class StandInGc {
 public:
  StandInGc();
  ~StandInGc();
  int port() const { return port_; }
  // Every CiInput received so far, in order.
  std::vector<CiInput> inputs() const;
  // The same, as the bytes that came over the wire.
  std::vector<std::string> wire() const;

 private:
  void serve();
  void handle(const std::string& bytes, int fd);
  void apply(const Change& change);
  std::optional<Referee::Command> tick(std::int64_t timestamp);
  void set_command(Referee::Command command);
  void send(int fd);

  int listener_ = -1;
  int port_ = 0;
  std::thread thread_;
  mutable std::mutex mutex_;
  std::vector<CiInput> inputs_;
  std::vector<std::string> wire_;
  Referee referee_;
  std::int64_t last_time_ = -1;  // ns
  std::int64_t command_since_ = 0;
  Team first_kickoff_ = YELLOW;
};

}  // namespace standin
