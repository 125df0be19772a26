#include "ubersim/gc_link/ci_client.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <thread>

namespace ubersim::gc_link {
namespace {

sockaddr_in parse_address(const std::string& address) {
  const auto colon = address.rfind(':');
  if (colon == std::string::npos) throw CiError("'" + address + "' is not HOST:PORT");
  std::string host = address.substr(0, colon);
  if (host.empty() || host == "localhost") host = "127.0.0.1";
  sockaddr_in out{};
  out.sin_family = AF_INET;
  int port = 0;
  try {
    port = std::stoi(address.substr(colon + 1));
  } catch (const std::exception&) {
    port = 0;
  }
  if (port <= 0 || port > 65535 || ::inet_pton(AF_INET, host.c_str(), &out.sin_addr) != 1) {
    throw CiError("'" + address + "' is not HOST:PORT with an IPv4 address");
  }
  out.sin_port = htons(static_cast<std::uint16_t>(port));
  return out;
}

}  // namespace

CiClient::CiClient(const std::string& address, std::chrono::milliseconds timeout) {
  const sockaddr_in target = parse_address(address);
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    if (fd_ < 0) throw CiError(std::string("cannot open a socket: ") + std::strerror(errno));
    if (::connect(fd_, reinterpret_cast<const sockaddr*>(&target), sizeof target) == 0) break;
    const int error = errno;
    ::close(fd_);
    fd_ = -1;
    if (std::chrono::steady_clock::now() >= deadline) {
      throw CiError("no game controller on " + address + " (" + std::strerror(error) +
                    "): is it running with -timeAcquisitionMode ci -ciAddress " + address + "?");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const int one = 1;  // small messages, one round trip each: no Nagle delay
  ::setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
}

CiClient::~CiClient() {
  if (fd_ >= 0) ::close(fd_);
}

void CiClient::send(const CiInput& input) {
  const std::string bytes = frame(input);
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw CiError(std::string("the game controller's CI connection broke: ") +
                    std::strerror(errno));
    sent += static_cast<std::size_t>(n);
  }
}

CiOutput CiClient::receive(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    if (auto bytes = reader_.next()) {
      CiOutput output;
      if (!output.ParseFromString(*bytes)) throw CiError("the game controller sent a bad CiOutput");
      return output;
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      throw CiError("no answer from the game controller within " +
                    std::to_string(timeout.count() / 1000) + " s");
    }
    pollfd p{fd_, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(left.count()));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    char buffer[65536];
    const ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw CiError("the game controller closed the CI connection");
    reader_.feed(std::string_view(buffer, static_cast<std::size_t>(n)));
  }
}

void CiClient::run(CiConversation& conversation, std::chrono::milliseconds timeout) {
  while (!conversation.done()) {
    if (auto input = conversation.next_input()) send(*input);
    conversation.on_output(receive(timeout));
  }
}

}  // namespace ubersim::gc_link
