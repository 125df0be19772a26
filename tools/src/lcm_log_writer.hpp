#pragma once
// An LCM log file (the format lcm-logger writes and lcm-logplayer reads),
// written so that a failure cannot go unnoticed: lcm::LogFile 1.3.1 writes
// through a buffered FILE* and never flushes or closes with a check, so on a
// full disk it loses messages silently and leaves a half-written last event.
// Here every event is one checked write(2) straight to the file; the first
// failure stops the writer, cuts the file back to the end of the last
// complete event (the log stays valid) and is kept with its errno text.
#include <sys/types.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ubersim {

class LcmLogWriter {
 public:
  // Creates or replaces the file; throws std::runtime_error when it cannot.
  explicit LcmLogWriter(std::string path);
  ~LcmLogWriter();  // closes the file if close() was not called
  LcmLogWriter(const LcmLogWriter&) = delete;
  LcmLogWriter& operator=(const LcmLogWriter&) = delete;

  // Appends one event (receive time in us since the epoch). Returns false,
  // and writes nothing more, once any write failed.
  bool write(const std::string& channel, const void* data, std::size_t size,
             std::int64_t timestamp_us);
  // Closes the file (checked: some file systems report errors only here).
  // Returns false if the log is not complete: a write or the close failed.
  bool close();

  bool failed() const { return !error_.empty(); }
  const std::string& error() const { return error_; }  // e.g. "No space left on device"
  std::int64_t events() const { return events_; }      // complete events in the file
  const std::string& path() const { return path_; }

 private:
  bool write_all(const unsigned char* bytes, std::size_t size);
  void fail(int errnum);

  std::string path_;
  int fd_ = -1;
  std::int64_t events_ = 0;
  off_t good_size_ = 0;  // the file's size after its last complete event
  std::vector<unsigned char> buffer_;
  std::string error_;
};

}  // namespace ubersim
