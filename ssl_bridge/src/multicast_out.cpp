#include "ubersim/ssl_bridge/multicast_out.hpp"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace ubersim::ssl {
namespace {

constexpr auto kMembershipRefresh = std::chrono::seconds(1);

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

bool is_multicast(const std::string& address) {
  in_addr parsed{};
  return ::inet_pton(AF_INET, address.c_str(), &parsed) == 1 && IN_MULTICAST(ntohl(parsed.s_addr));
}

std::string ttl_meaning(int ttl) {
  if (ttl == 0) return "this host only";
  if (ttl == 1) return "this host and its local network";
  return "this host and up to " + std::to_string(ttl) + " routers away";
}

}  // namespace

std::string interface_name(const std::string& address) {
  ifaddrs* list = nullptr;
  if (::getifaddrs(&list) != 0) return "?";
  std::string name = "?";
  for (const ifaddrs* entry = list; entry != nullptr; entry = entry->ifa_next) {
    if (entry->ifa_addr == nullptr || entry->ifa_addr->sa_family != AF_INET) continue;
    char text[INET_ADDRSTRLEN] = {};
    const auto* ipv4 = reinterpret_cast<const sockaddr_in*>(entry->ifa_addr);
    if (::inet_ntop(AF_INET, &ipv4->sin_addr, text, sizeof text) != nullptr && address == text) {
      name = entry->ifa_name;
      break;
    }
  }
  ::freeifaddrs(list);
  return name;
}

std::string route_device(const std::string& group, const std::string& routes) {
  in_addr parsed{};
  if (::inet_pton(AF_INET, group.c_str(), &parsed) != 1) return {};
  std::stringstream lines(routes);
  std::string line;
  std::getline(lines, line);  // the header
  std::string best;
  int best_prefix = -1;
  long best_metric = 0;
  while (std::getline(lines, line)) {
    std::stringstream fields(line);
    std::string device, destination, gateway, flags, refcnt, use, metric, mask;
    if (!(fields >> device >> destination >> gateway >> flags >> refcnt >> use >> metric >> mask)) {
      continue;
    }
    try {
      const auto dest = static_cast<std::uint32_t>(std::stoul(destination, nullptr, 16));
      const auto bits = static_cast<std::uint32_t>(std::stoul(mask, nullptr, 16));
      const bool up = (std::stoul(flags, nullptr, 16) & 0x1U) != 0;  // RTF_UP
      const int prefix = __builtin_popcount(bits);
      const long cost = std::stol(metric);
      if (!up || (parsed.s_addr & bits) != dest) continue;
      if (prefix > best_prefix || (prefix == best_prefix && cost < best_metric)) {
        best = device;
        best_prefix = prefix;
        best_metric = cost;
      }
    } catch (const std::exception&) {
      continue;  // not a route line
    }
  }
  return best;
}

std::string interface_address(const std::string& device) {
  ifaddrs* list = nullptr;
  if (::getifaddrs(&list) != 0) return {};
  std::string address;
  for (const ifaddrs* entry = list; entry != nullptr; entry = entry->ifa_next) {
    if (entry->ifa_addr == nullptr || entry->ifa_addr->sa_family != AF_INET) continue;
    if (device != entry->ifa_name) continue;
    char text[INET_ADDRSTRLEN] = {};
    const auto* ipv4 = reinterpret_cast<const sockaddr_in*>(entry->ifa_addr);
    if (::inet_ntop(AF_INET, &ipv4->sin_addr, text, sizeof text) != nullptr) address = text;
    break;
  }
  ::freeifaddrs(list);
  return address;
}

std::optional<OutInterface> route_interface(const std::string& group, std::string& why) {
  // connect() on a UDP socket asks the routing table, as a join on 0.0.0.0
  // does; the source address it picks belongs to the interface of the route.
  const sockaddr_in destination = make_address(group, 9);
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) {
    why = std::string("socket: ") + std::strerror(errno);
    return std::nullopt;
  }
  sockaddr_in source{};
  socklen_t length = sizeof source;
  const bool found =
      ::connect(fd, reinterpret_cast<const sockaddr*>(&destination), sizeof destination) == 0 &&
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&source), &length) == 0;
  const int error = errno;
  ::close(fd);
  if (!found) {
    why = "no route to " + group + " (" + std::strerror(error) + ")";
    return std::nullopt;
  }
  char text[INET_ADDRSTRLEN] = {};
  ::inet_ntop(AF_INET, &source.sin_addr, text, sizeof text);
  if (source.sin_addr.s_addr != htonl(INADDR_ANY)) return OutInterface{text, interface_name(text)};
  // A route to a device without naming a source (e.g. "224.0.0.0/4 dev lo":
  // lo's 127.0.0.1 is host scope, never picked as the source of a link-scope
  // route): the device is the routing table's, its address the device's.
  std::ifstream file("/proc/net/route");
  std::stringstream routes;
  routes << file.rdbuf();
  const std::string device = route_device(group, routes.str());
  const std::string address = device.empty() ? std::string() : interface_address(device);
  if (address.empty()) {
    why = "the route to " + group + " names no interface with an IPv4 address";
    return std::nullopt;
  }
  return OutInterface{address, device};
}

std::vector<OutInterface> resolve_interfaces(const std::string& list, const std::string& group,
                                             std::vector<std::string>& warnings) {
  std::vector<OutInterface> result;
  std::stringstream entries(list);
  std::string entry;
  while (std::getline(entries, entry, ',')) {
    entry = trim(entry);
    if (entry.empty()) continue;
    OutInterface out;
    if (entry == kDefaultInterface) {
      std::string why;
      const auto routed = route_interface(group, why);
      if (!routed) {
        warnings.push_back("no default interface: " + why);
        continue;
      }
      out = *routed;
      out.routed = true;
    } else {
      make_address(entry, 1);  // throws naming a bad address
      out = OutInterface{entry, interface_name(entry)};
    }
    const auto same = std::find_if(result.begin(), result.end(),
                                   [&](const OutInterface& o) { return o.address == out.address; });
    if (same == result.end()) {
      result.push_back(out);
    } else {
      same->routed = same->routed || out.routed;
    }
  }
  return result;
}

void GroupMemberships::refresh() {
  std::ifstream file(path_);
  std::stringstream text;
  text << file.rdbuf();
  parse(file ? text.str() : std::string());
}

// /proc/net/igmp: a line per device ("1\tlo        :     2      V3"), then a
// line per group it joined, indented ("\t\t\t\t020517E0     1 0:00000000\t\t0"),
// the group as the hex of its 32 bits as they lie in memory.
void GroupMemberships::parse(const std::string& text) {
  groups_by_device_.clear();
  std::stringstream lines(text);
  std::string line;
  std::string device;
  while (std::getline(lines, line)) {
    if (line.empty()) continue;
    std::stringstream fields(line);
    if (line[0] != '\t' && line[0] != ' ') {
      std::string index;
      fields >> index >> device;
      if (!device.empty() && device.back() == ':') device.pop_back();
      continue;
    }
    std::string hex;
    fields >> hex;
    if (device.empty() || hex.size() != 8) continue;
    try {
      groups_by_device_[device].push_back(static_cast<std::uint32_t>(std::stoul(hex, nullptr, 16)));
    } catch (const std::exception&) {
      continue;  // not a group line
    }
  }
}

bool GroupMemberships::joined(const std::string& device, const std::string& group) const {
  in_addr parsed{};
  if (::inet_pton(AF_INET, group.c_str(), &parsed) != 1) return false;
  const auto found = groups_by_device_.find(device);
  if (found == groups_by_device_.end()) return false;
  return std::find(found->second.begin(), found->second.end(), parsed.s_addr) !=
         found->second.end();
}

MulticastStream::MulticastStream(const StreamSettings& settings)
    : settings_(settings),
      destination_(make_address(settings.group, settings.port)),
      multicast_(is_multicast(settings.group)) {
  if (!multicast_) {
    // A unicast destination: the routing table picks the way, once.
    interfaces_.push_back(OutInterface{"0.0.0.0", "(routed)"});
    sockets_.push_back(UdpSocket::multicast_sender(settings_.ttl, "0.0.0.0"));
    return;
  }
  interfaces_ = resolve_interfaces(settings_.interfaces, settings_.group, warnings_);
  if (interfaces_.empty()) {
    throw std::invalid_argument(settings_.name + ": no interface to send " + settings_.group +
                                " on (" + settings_.interfaces + ")");
  }
  for (const OutInterface& out : interfaces_) {
    sockets_.push_back(UdpSocket::multicast_sender(settings_.ttl, out.address));
  }
}

bool MulticastStream::loopback_copy_needed(std::chrono::steady_clock::time_point now) {
  if (now - memberships_read_ >= kMembershipRefresh) {
    memberships_read_ = now;
    memberships_.refresh();
    loopback_needed_ = std::none_of(interfaces_.begin(), interfaces_.end(), [&](const auto& out) {
      return !out.loopback() && memberships_.joined(out.device, settings_.group);
    });
  }
  return loopback_needed_;
}

bool MulticastStream::send(const std::string& bytes) {
  const bool other_than_lo = std::any_of(interfaces_.begin(), interfaces_.end(),
                                         [](const OutInterface& out) { return !out.loopback(); });
  const bool lo_copy =
      !multicast_ || !other_than_lo || loopback_copy_needed(std::chrono::steady_clock::now());
  bool ok = true;
  for (std::size_t i = 0; i < sockets_.size(); ++i) {
    if (multicast_ && interfaces_[i].loopback() && !lo_copy) {
      ++loopback_skipped_;
      continue;
    }
    ok = sockets_[i].send_to(bytes, destination_) && ok;
  }
  return ok;
}

void MulticastStream::set_port(int port) {
  destination_.sin_port = htons(static_cast<std::uint16_t>(port));
  settings_.port = port;
}

std::string MulticastStream::describe() const {
  std::string text = settings_.name + " to " + settings_.group + ":" +
                     std::to_string(settings_.port) + " (ttl " + std::to_string(settings_.ttl) +
                     ": " + ttl_meaning(settings_.ttl) + ")";
  if (!multicast_) return text + ", unicast";
  const bool other_than_lo = std::any_of(interfaces_.begin(), interfaces_.end(),
                                         [](const OutInterface& out) { return !out.loopback(); });
  for (std::size_t i = 0; i < interfaces_.size(); ++i) {
    const OutInterface& out = interfaces_[i];
    text += (i == 0 ? " on " : " and on ") + out.device + " " + out.address;
    if (out.loopback() && other_than_lo) {
      text += " (only while nobody on this host joined on the other interface)";
    }
  }
  const bool routed = std::any_of(interfaces_.begin(), interfaces_.end(),
                                  [](const OutInterface& out) { return out.routed; });
  if (!other_than_lo && routed) {
    text += "; the kernel routes " + settings_.group +
            " to lo: a program joining on 0.0.0.0 or on 127.0.0.1 hears it";
  } else if (!other_than_lo) {
    text +=
        "; a program hears it when it joins on 127.0.0.1 (one joining on 0.0.0.0 joins "
        "where the kernel routes " +
        settings_.group + ")";
  } else {
    text += "; a program joining on 0.0.0.0 or on 127.0.0.1 hears it once";
  }
  return text;
}

}  // namespace ubersim::ssl
