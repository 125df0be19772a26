#pragma once
// The framing of the game controller's CI port (and of its other TCP ports):
// every protobuf message is preceded by its size as a base-128 varint
// (protobuf's "size-delimited" form; RoboCup-SSL/ssl-game-controller
// internal/app/sslconn). Pure: bytes in, messages out, no socket.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace google::protobuf {
class MessageLite;
}

namespace ubersim::gc_link {

class FramingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The size varint followed by the message's bytes, serialised
// deterministically (map entries in key order).
std::string frame(const google::protobuf::MessageLite& message);

// Collects bytes as they come off a stream and cuts them into messages.
class FrameReader {
 public:
  // A message larger than this is an error (the GC's CiOutput is a few KB).
  static constexpr std::size_t kMaxMessageSize = 16u << 20;

  void feed(std::string_view bytes);
  // The next whole message's bytes, or nothing until more bytes arrive.
  // Throws FramingError on a size varint longer than 10 bytes or a size over
  // kMaxMessageSize: the stream cannot be resynchronised after that.
  std::optional<std::string> next();
  std::size_t buffered() const { return buffer_.size() - read_; }

 private:
  std::string buffer_;
  std::size_t read_ = 0;  // bytes of buffer_ already handed out
};

}  // namespace ubersim::gc_link
