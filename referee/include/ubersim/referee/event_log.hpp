#pragma once
// The event log a referee writes with --events (JSON lines: ubersim_referee
// auto and ubersim_gc_link). Each line is flushed as it is written, so a run
// stopped at any moment leaves whole lines.
#include <fstream>
#include <stdexcept>
#include <string>

namespace ubersim::referee {

class EventLog {
 public:
  // An empty path writes nothing. Throws std::runtime_error when the file
  // cannot be written.
  explicit EventLog(const std::string& path) {
    if (path.empty()) return;
    file_.open(path);
    if (!file_) throw std::runtime_error("cannot write the event log " + path);
  }

  void write(const std::string& line) {
    if (file_.is_open()) file_ << line << "\n" << std::flush;
  }

 private:
  std::ofstream file_;
};

}  // namespace ubersim::referee
