#pragma once
// A program started by a test, a benchmark or the report (physics, an
// emulator, a demo team): stdout and stderr go to a log file, stop() asks it
// to end with SIGTERM (or another signal), and the destructor makes sure
// nothing is left running.
#include <sys/types.h>

#include <string>
#include <vector>

namespace ubersim {

class ChildProcess {
 public:
  // argv[0] is the program's path. log_path "" sends output to /dev/null.
  ChildProcess(const std::vector<std::string>& argv, const std::string& log_path);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  const std::string& name() const { return name_; }  // the program's file name
  bool running();
  // Sends `signal_number` and waits (up to timeout_s) for the exit; returns the
  // exit status (0..255), 128 + signal if killed by one, -1 if it did not end
  // in time (it is then killed with SIGKILL).
  int stop(double timeout_s = 10, int signal_number = 15 /* SIGTERM */);
  // Waits up to timeout_s for it to end by itself; returns as stop() does.
  int wait(double timeout_s);
  std::string log() const;  // what it wrote so far
  // Waits up to timeout_s for `text` to appear in its output (a process
  // saying it is ready); false if it did not.
  bool wait_for_output(const std::string& text, double timeout_s) const;

 private:
  pid_t pid_ = -1;
  int status_ = -1;
  bool reaped_ = false;
  std::string name_;
  std::string log_path_;
};

// True while a process with this pid exists (and is not a zombie).
bool process_alive(pid_t pid);

}  // namespace ubersim
