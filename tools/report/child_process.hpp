#pragma once
// A program the report starts (physics, an emulator, a demo team): its output
// goes to a log file, stop() ends it with SIGTERM and returns its exit code,
// and the destructor makes sure nothing is left running. (The tests have a
// similar helper in tests/support; a tool does not link test code.)
#include <sys/types.h>

#include <string>
#include <vector>

namespace ubersim::report {

class ChildProcess {
 public:
  // argv[0] is the program's path; log_path "" sends its output to /dev/null.
  ChildProcess(const std::vector<std::string>& argv, std::string log_path);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  const std::string& name() const { return name_; }
  bool running();
  // Sends SIGTERM and waits up to timeout_s; returns the exit status (0..255),
  // 128 + signal when a signal ended it, -1 when it had to be killed.
  int stop(double timeout_s = 10);
  std::string log() const;  // what it has written so far

 private:
  pid_t pid_ = -1;
  int status_ = -1;
  bool reaped_ = false;
  std::string name_;
  std::string log_path_;
};

}  // namespace ubersim::report
