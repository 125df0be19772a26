#include "ubersim/gc_link/ci_framing.hpp"

#include <google/protobuf/io/coded_stream.h>
#include <google/protobuf/io/zero_copy_stream_impl_lite.h>
#include <google/protobuf/message_lite.h>

namespace ubersim::gc_link {

std::string frame(const google::protobuf::MessageLite& message) {
  // Deterministic: map entries (the GC's config deltas have maps) in key
  // order, so that two runs send the same bytes.
  std::string body;
  {
    google::protobuf::io::StringOutputStream stream(&body);
    google::protobuf::io::CodedOutputStream coded(&stream);
    coded.SetSerializationDeterministic(true);
    message.SerializeToCodedStream(&coded);
  }
  std::string out;
  std::uint64_t size = body.size();
  do {
    auto byte = static_cast<unsigned char>(size & 0x7f);
    size >>= 7;
    if (size != 0) byte |= 0x80;
    out.push_back(static_cast<char>(byte));
  } while (size != 0);
  return out + body;
}

void FrameReader::feed(std::string_view bytes) {
  if (read_ > 0 && read_ == buffer_.size()) {
    buffer_.clear();
    read_ = 0;
  }
  buffer_.append(bytes);
}

std::optional<std::string> FrameReader::next() {
  std::uint64_t size = 0;
  std::size_t pos = read_;
  for (int shift = 0;; shift += 7) {
    if (shift >= 70) throw FramingError("CI stream: a size varint longer than 10 bytes");
    if (pos >= buffer_.size()) return std::nullopt;  // the size is not complete yet
    const auto byte = static_cast<unsigned char>(buffer_[pos++]);
    size |= static_cast<std::uint64_t>(byte & 0x7f) << shift;
    if ((byte & 0x80) == 0) break;
  }
  if (size > kMaxMessageSize) {
    throw FramingError("CI stream: a message of " + std::to_string(size) +
                       " bytes, more than the limit of " + std::to_string(kMaxMessageSize));
  }
  if (buffer_.size() - pos < size) return std::nullopt;
  std::string message = buffer_.substr(pos, size);
  read_ = pos + size;
  // Drop what was read once it is most of the buffer, so memory stays bounded.
  if (read_ > 4096 && read_ * 2 > buffer_.size()) {
    buffer_.erase(0, read_);
    read_ = 0;
  }
  return message;
}

}  // namespace ubersim::gc_link
