#include "ubersim/lcm_channel_filter.hpp"

#include <sys/socket.h>

#include <cstdint>
#include <string_view>

namespace ubersim {
namespace {

// LCM's wire format (lcm_udpm.c): a 4-byte magic, a 4-byte sequence number,
// then (short messages) the channel name and its NUL.
constexpr std::uint32_t kShortMessageMagic = 0x4c433032;  // "LC02"
constexpr std::uint32_t kFragmentMagic = 0x4c433033;      // "LC03"
constexpr std::uint32_t kUdpHeaderSize = 8;
constexpr std::uint32_t kMagicOffset = kUdpHeaderSize;
constexpr std::uint32_t kChannelOffset = kUdpHeaderSize + 8;
constexpr std::size_t kMaxChannelLength = 63;   // LCM_MAX_CHANNEL_NAME_LENGTH
constexpr std::uint32_t kAccept = 0xffffffffU;  // keep the whole datagram
constexpr std::uint32_t kDrop = 0;
// What makes LCM read a subscription as more than a plain name.
constexpr std::string_view kRegexCharacters = ".[]{}()\\*+?^$|";

sock_filter statement(std::uint16_t code, std::uint32_t k) {
  return BPF_STMT(code, k);
}
sock_filter jump_if_equal(std::uint32_t k, std::uint8_t if_equal, std::uint8_t if_not) {
  return BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, k, if_equal, if_not);
}

// One block per channel: compare its name and NUL in words, then a half word
// and a byte for the rest (never reading past the NUL: a message may end
// right after it), and accept; any difference jumps to the next block.
void append_channel_block(const std::string& channel, std::vector<sock_filter>& program) {
  const std::string bytes = channel + '\0';
  struct Load {
    std::uint16_t size_code;
    std::uint32_t offset;
    std::uint32_t value;
  };
  std::vector<Load> loads;
  std::size_t at = 0;
  while (at < bytes.size()) {
    const std::size_t left = bytes.size() - at;
    const std::size_t width = left >= 4 ? 4 : left >= 2 ? 2 : 1;
    std::uint32_t value = 0;
    for (std::size_t i = 0; i < width; ++i) {
      value = (value << 8) | static_cast<unsigned char>(bytes[at + i]);
    }
    const std::uint16_t size_code = width == 4 ? BPF_W : width == 2 ? BPF_H : BPF_B;
    loads.push_back({size_code, kChannelOffset + static_cast<std::uint32_t>(at), value});
    at += width;
  }
  const std::size_t block_size = 2 * loads.size() + 1;
  for (std::size_t i = 0; i < loads.size(); ++i) {
    program.push_back(statement(BPF_LD | loads[i].size_code | BPF_ABS, loads[i].offset));
    // From the jump after this load to the next block's first instruction.
    const auto to_next_block = static_cast<std::uint8_t>(block_size - (2 * i + 2));
    program.push_back(jump_if_equal(loads[i].value, 0, to_next_block));
  }
  program.push_back(statement(BPF_RET | BPF_K, kAccept));
}

}  // namespace

bool is_plain_channel_name(const std::string& channel) {
  if (channel.empty() || channel.size() > kMaxChannelLength) return false;
  for (const char c : channel) {
    if (kRegexCharacters.find(c) != std::string_view::npos) return false;
  }
  return true;
}

std::vector<sock_filter> lcm_channel_filter_program(const std::set<std::string>& channels) {
  std::vector<sock_filter> program{
      statement(BPF_LD | BPF_W | BPF_ABS, kMagicOffset),
      jump_if_equal(kFragmentMagic, 0, 1),
      statement(BPF_RET | BPF_K, kAccept),
      jump_if_equal(kShortMessageMagic, 1, 0),
      statement(BPF_RET | BPF_K, kDrop),
  };
  for (const std::string& channel : channels) append_channel_block(channel, program);
  program.push_back(statement(BPF_RET | BPF_K, kDrop));
  return program;
}

bool attach_lcm_channel_filter(int socket_fd, const std::set<std::string>& channels) {
  std::vector<sock_filter> program = lcm_channel_filter_program(channels);
  if (program.size() > BPF_MAXINSNS) return false;
  const sock_fprog fprog{static_cast<unsigned short>(program.size()), program.data()};
  return ::setsockopt(socket_fd, SOL_SOCKET, SO_ATTACH_FILTER, &fprog, sizeof fprog) == 0;
}

void detach_lcm_channel_filter(int socket_fd) {
  int unused = 0;
  ::setsockopt(socket_fd, SOL_SOCKET, SO_DETACH_FILTER, &unused, sizeof unused);
}

}  // namespace ubersim
