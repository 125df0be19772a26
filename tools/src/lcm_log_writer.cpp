#include "lcm_log_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace ubersim {
namespace {

// LCM's event header (lcm/eventlog.c): sync word, event number, timestamp,
// channel length, data length, all big-endian; then channel and data.
constexpr std::uint32_t kSyncWord = 0xEDA1DA01;

template <class T>
void put_big_endian(std::vector<unsigned char>& out, T value) {
  for (int shift = 8 * static_cast<int>(sizeof(T)) - 8; shift >= 0; shift -= 8) {
    out.push_back(static_cast<unsigned char>((static_cast<std::uint64_t>(value) >> shift) & 0xff));
  }
}

}  // namespace

LcmLogWriter::LcmLogWriter(std::string path) : path_(std::move(path)) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    throw std::runtime_error("cannot write the log '" + path_ + "': " + std::strerror(errno));
  }
}

LcmLogWriter::~LcmLogWriter() {
  if (fd_ >= 0) ::close(fd_);
}

bool LcmLogWriter::write(const std::string& channel, const void* data, std::size_t size,
                         std::int64_t timestamp_us) {
  if (failed() || fd_ < 0) return false;
  // One buffer, one write: an event is in the file whole or (cut off below) not at all.
  buffer_.clear();
  put_big_endian(buffer_, kSyncWord);
  put_big_endian(buffer_, events_);
  put_big_endian(buffer_, timestamp_us);
  put_big_endian(buffer_, static_cast<std::int32_t>(channel.size()));
  put_big_endian(buffer_, static_cast<std::int32_t>(size));
  buffer_.insert(buffer_.end(), channel.begin(), channel.end());
  const auto* bytes = static_cast<const unsigned char*>(data);
  buffer_.insert(buffer_.end(), bytes, bytes + size);
  if (!write_all(buffer_.data(), buffer_.size())) return false;
  good_size_ += static_cast<off_t>(buffer_.size());
  ++events_;
  return true;
}

bool LcmLogWriter::write_all(const unsigned char* bytes, std::size_t size) {
  while (size > 0) {
    const ssize_t written = ::write(fd_, bytes, size);
    if (written < 0) {
      if (errno == EINTR) continue;  // a signal (Ctrl-C) is not a failure of the file
      fail(errno);
      return false;
    }
    // A short write is how a file system that just filled up answers; the
    // next write then says why.
    bytes += written;
    size -= static_cast<std::size_t>(written);
  }
  return true;
}

void LcmLogWriter::fail(int errnum) {
  error_ = std::strerror(errnum);
  // Cut off the part of the event that did get in, so that every reader
  // (lcm-logplayer, lcm::LogFile) sees a log that ends with a whole event.
  // Shrinking a file needs no space, so this works on a full disk.
  if (::ftruncate(fd_, good_size_) != 0) {
    error_ += std::string(" (and cutting off the partial last event failed too: ") +
              std::strerror(errno) + ")";
  }
}

bool LcmLogWriter::close() {
  if (fd_ < 0) return !failed();
  const int fd = std::exchange(fd_, -1);
  if (::close(fd) != 0 && !failed()) error_ = std::strerror(errno);
  return !failed();
}

}  // namespace ubersim
