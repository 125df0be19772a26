#include "ubersim/physics/single_instance.hpp"

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstring>
#include <functional>
#include <sstream>
#include <utility>

#include "ubersim/lcm_udpm_receiver.hpp"

namespace ubersim::physics {
namespace {

// An abstract address: sun_path starts with a NUL, the name follows, and its
// length is the address's length (no terminating NUL).
sockaddr_un abstract_address(const std::string& name, socklen_t& length) {
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  const std::size_t size = std::min(name.size(), sizeof address.sun_path - 1);
  std::memcpy(address.sun_path + 1, name.data(), size);
  length = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + 1 + size);
  return address;
}

int open_unix_socket() {
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) throw std::runtime_error(std::string("bus claim: socket: ") + std::strerror(errno));
  return fd;
}

// What the user reads when the bus is taken: who holds it, and the two ways
// to run beside it.
std::string taken_message(const LcmUdpmAddress& address, const std::string& prefix,
                          std::optional<pid_t> holder) {
  std::ostringstream line;
  line << "another ubersim_physics";
  if (holder) line << " (pid " << *holder << ")";
  line << " already runs on LCM port " << address.port;
  line << (prefix.empty() ? " with no channel prefix" : " with channel prefix '" + prefix + "'");
  line << ": two on one bus corrupt both runs. To run beside it, give every program of this run "
       << "another port (--lcm-url udpm://" << address.group << ":"
       << (address.port < 65535 ? address.port + 1 : address.port - 1)
       << "?ttl=0) or a channel prefix (--channel-prefix "
       << (prefix.empty() ? "run2_" : prefix + "2_") << "); tools/launch.sh takes both";
  return line.str();
}

}  // namespace

std::optional<std::string> bus_claim_name(const std::string& lcm_url,
                                          const std::string& channel_prefix) {
  const auto address = parse_lcm_udpm_url(lcm_url);
  if (!address) return std::nullopt;
  std::string name = "ubersim/physics/lcm-port=" + std::to_string(address->port) + "/prefix=";
  // A prefix too long for sun_path is named by its hash (same prefix, same name).
  constexpr std::size_t kRoom = sizeof(sockaddr_un::sun_path) - 1;
  if (name.size() + channel_prefix.size() <= kRoom) return name + channel_prefix;
  return name + "#" + std::to_string(std::hash<std::string>{}(channel_prefix));
}

std::optional<pid_t> bus_claim_holder(const std::string& name) {
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd < 0) return std::nullopt;
  socklen_t length = 0;
  const sockaddr_un address = abstract_address(name, length);
  std::optional<pid_t> pid;
  // The connection waits in the holder's queue, never accepted: the kernel
  // knows the listener's credentials from its listen() call.
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&address), length) == 0) {
    ucred credentials{};
    socklen_t size = sizeof credentials;
    if (::getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &credentials, &size) == 0 &&
        credentials.pid > 0) {
      pid = credentials.pid;
    }
  }
  ::close(fd);
  return pid;
}

BusClaim BusClaim::claim(const std::string& lcm_url, const std::string& channel_prefix) {
  const auto name = bus_claim_name(lcm_url, channel_prefix);
  if (!name) return BusClaim(-1);
  const int fd = open_unix_socket();
  socklen_t length = 0;
  const sockaddr_un address = abstract_address(*name, length);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&address), length) != 0) {
    const int error = errno;
    ::close(fd);
    if (error == EADDRINUSE) {
      throw BusTaken(
          taken_message(*parse_lcm_udpm_url(lcm_url), channel_prefix, bus_claim_holder(*name)));
    }
    throw std::runtime_error(std::string("bus claim: bind: ") + std::strerror(error));
  }
  // Listening lets a second start ask who holds it; the queue bounds how many
  // unanswered askers it remembers (past it they get no pid, still the refusal).
  if (::listen(fd, SOMAXCONN) != 0) {
    const int error = errno;
    ::close(fd);
    throw std::runtime_error(std::string("bus claim: listen: ") + std::strerror(error));
  }
  return BusClaim(fd);
}

void BusClaim::check(const std::string& lcm_url, const std::string& channel_prefix) {
  const auto name = bus_claim_name(lcm_url, channel_prefix);
  if (!name) return;
  if (const auto holder = bus_claim_holder(*name)) {
    throw BusTaken(taken_message(*parse_lcm_udpm_url(lcm_url), channel_prefix, holder));
  }
}

BusClaim::BusClaim(BusClaim&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}

BusClaim& BusClaim::operator=(BusClaim&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

BusClaim::~BusClaim() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace ubersim::physics
