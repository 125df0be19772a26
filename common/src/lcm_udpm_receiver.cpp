#include "ubersim/lcm_udpm_receiver.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <linux/sock_diag.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <regex>
#include <stdexcept>

#include "ubersim/lcm_channel_filter.hpp"

namespace ubersim {
namespace {

constexpr char kShortMessageMagic[] = {'L', 'C', '0', '2'};
constexpr char kFragmentMagic[] = {'L', 'C', '0', '3'};
constexpr std::size_t kShortHeaderBytes = 8;  // magic, sequence number
constexpr std::size_t kMaxChannelBytes = 63;

[[noreturn]] void fail(const std::string& what) {
  throw std::runtime_error("LCM receive socket: " + what + ": " + std::strerror(errno));
}

std::int64_t now_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::int64_t receive_time_us(msghdr& header) {
  for (cmsghdr* control = CMSG_FIRSTHDR(&header); control != nullptr;
       control = CMSG_NXTHDR(&header, control)) {
    if (control->cmsg_level == SOL_SOCKET && control->cmsg_type == SCM_TIMESTAMP) {
      timeval stamp{};
      std::memcpy(&stamp, CMSG_DATA(control), sizeof stamp);
      return static_cast<std::int64_t>(stamp.tv_sec) * 1000000 + stamp.tv_usec;
    }
  }
  return now_us();
}

}  // namespace

std::optional<LcmUdpmAddress> parse_lcm_udpm_url(const std::string& url) {
  std::string effective = url;
  if (effective.empty()) {
    const char* from_environment = std::getenv("LCM_DEFAULT_URL");
    effective = from_environment != nullptr ? from_environment : "udpm://239.255.76.67:7667";
  }
  static const std::regex udpm(
      R"(^udpm://([0-9]{1,3}(?:\.[0-9]{1,3}){3}):([0-9]{1,5})(?:\?(.*))?$)");
  std::smatch match;
  if (!std::regex_match(effective, match, udpm)) return std::nullopt;
  LcmUdpmAddress address;
  address.group = match[1];
  address.port = std::stoi(match[2]);
  if (address.port <= 0 || address.port > 65535) return std::nullopt;
  static const std::regex option(R"(([a-z_]+)=([^&]*))");
  const std::string options = match[3];
  for (auto it = std::sregex_iterator(options.begin(), options.end(), option);
       it != std::sregex_iterator(); ++it) {
    if ((*it)[1] == "recv_buf_size") {
      address.receive_buffer_bytes =
          static_cast<int>(std::strtol((*it)[2].str().c_str(), nullptr, 10));
    }
  }
  return address;
}

LcmUdpmReceiver::LcmUdpmReceiver(const LcmUdpmAddress& address)
    : buffers_(static_cast<std::size_t>(kBatch) * kDatagramBytes) {
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) fail("socket");
  // As LCM sets up its own: every process on the host shares the port.
  const int on = 1;
  if (::setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on) != 0 ||
      ::setsockopt(fd_, SOL_SOCKET, SO_REUSEPORT, &on, sizeof on) != 0 ||
      ::setsockopt(fd_, SOL_SOCKET, SO_TIMESTAMP, &on, sizeof on) != 0) {
    ::close(fd_);
    fail("options");
  }
  if (address.receive_buffer_bytes > 0) {
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &address.receive_buffer_bytes,
                 sizeof address.receive_buffer_bytes);
  }
  // Nothing reaches the process until it subscribes.
  attach_lcm_channel_filter(fd_, {});
  sockaddr_in bound{};
  bound.sin_family = AF_INET;
  bound.sin_addr.s_addr = htonl(INADDR_ANY);
  bound.sin_port = htons(static_cast<std::uint16_t>(address.port));
  ip_mreq membership{};
  if (::inet_pton(AF_INET, address.group.c_str(), &membership.imr_multiaddr) != 1 ||
      ::bind(fd_, reinterpret_cast<const sockaddr*>(&bound), sizeof bound) != 0 ||
      ::setsockopt(fd_, IPPROTO_IP, IP_ADD_MEMBERSHIP, &membership, sizeof membership) != 0) {
    const int error = errno;
    ::close(fd_);
    errno = error;
    fail("join " + address.group + ":" + std::to_string(address.port));
  }
}

LcmUdpmReceiver::~LcmUdpmReceiver() {
  ::close(fd_);
}

void LcmUdpmReceiver::want_channels(const std::set<std::string>& channels) {
  if (!attach_lcm_channel_filter(fd_, channels)) {
    // Never keep an older filter that lacks a channel: receive everything
    // (receive() still delivers only what the caller asks for).
    detach_lcm_channel_filter(fd_);
  }
}

int LcmUdpmReceiver::receive(int budget, const Deliver& deliver, const Drop& drop,
                             const std::function<void()>& before_delivering) {
  int read = 0;
  std::array<mmsghdr, kBatch> headers{};
  std::array<iovec, kBatch> vectors{};
  std::array<std::array<char, CMSG_SPACE(sizeof(timeval))>, kBatch> controls{};
  while (budget > 0) {
    const int batch = budget < kBatch ? budget : kBatch;
    for (int i = 0; i < batch; ++i) {
      vectors[i] = {buffers_.data() + static_cast<std::size_t>(i) * kDatagramBytes, kDatagramBytes};
      headers[i] = {};
      headers[i].msg_hdr.msg_iov = &vectors[i];
      headers[i].msg_hdr.msg_iovlen = 1;
      headers[i].msg_hdr.msg_control = controls[i].data();
      headers[i].msg_hdr.msg_controllen = controls[i].size();
    }
    const int received =
        ::recvmmsg(fd_, headers.data(), static_cast<unsigned>(batch), MSG_DONTWAIT, nullptr);
    if (received <= 0) break;  // nothing more (EAGAIN) or an error the next poll shows
    budget -= received;
    read += received;
    if (before_delivering) before_delivering();
    for (int i = 0; i < received; ++i) {
      const char* data = static_cast<const char*>(vectors[i].iov_base);
      const std::size_t size = headers[i].msg_len;
      if (size >= 4 && std::memcmp(data, kFragmentMagic, 4) == 0) {
        drop("fragment", size);
        continue;
      }
      if ((headers[i].msg_hdr.msg_flags & MSG_TRUNC) != 0 || size < kShortHeaderBytes + 1 ||
          std::memcmp(data, kShortMessageMagic, 4) != 0) {
        drop("not LCM", size);
        continue;
      }
      const char* channel = data + kShortHeaderBytes;
      const std::size_t room = size - kShortHeaderBytes;
      const auto* end = static_cast<const char*>(
          std::memchr(channel, '\0', room < kMaxChannelBytes + 1 ? room : kMaxChannelBytes + 1));
      if (end == nullptr || end == channel) {
        drop("not LCM", size);
        continue;
      }
      const char* payload = end + 1;
      deliver(channel, payload, static_cast<std::size_t>(data + size - payload),
              receive_time_us(headers[i].msg_hdr));
    }
    if (received < batch) break;
  }
  return read;
}

std::uint64_t LcmUdpmReceiver::kernel_drops() const {
  std::array<std::uint32_t, SK_MEMINFO_VARS> meminfo{};
  socklen_t size = sizeof meminfo;
  if (::getsockopt(fd_, SOL_SOCKET, SO_MEMINFO, meminfo.data(), &size) != 0) return 0;
  return meminfo[SK_MEMINFO_DROPS];
}

}  // namespace ubersim
