#pragma once
// A program started by a test: stdout and stderr go to a log file, SIGTERM asks
// it to stop, and the destructor makes sure nothing is left running.
#include <sys/types.h>

#include <string>
#include <vector>

namespace radio_test {

class ChildProcess {
 public:
  ChildProcess(const std::vector<std::string>& argv, const std::string& log_path);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  bool running();
  // Sends SIGTERM and waits (up to timeout_s) for the exit; returns the exit
  // status (0..255), 128 + signal if killed by one, -1 if it had to be killed.
  int terminate(double timeout_s = 10);
  std::string log() const;  // what it wrote so far

 private:
  pid_t pid_ = -1;
  int status_ = -1;
  bool reaped_ = false;
  std::string log_path_;
};

}  // namespace radio_test
