// Which process holds a UDP socket (socket_owner.hpp).
#include "ubersim/ssl_bridge/socket_owner.hpp"

#include <dirent.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <sstream>

namespace ubersim::ssl {

std::vector<unsigned long> udp_socket_inodes(const std::string& table, std::uint16_t port) {
  std::vector<unsigned long> inodes;
  std::istringstream lines(table);
  std::string line;
  std::getline(lines, line);  // the heading
  while (std::getline(lines, line)) {
    // "sl local_address rem_address st tx_queue:rx_queue tr:tm->when retrnsmt uid timeout inode
    // ..."
    std::istringstream fields(line);
    std::string slot, local, remote, state, queues, timer, retransmits, uid, timeout;
    unsigned long inode = 0;
    if (!(fields >> slot >> local >> remote >> state >> queues >> timer >> retransmits >> uid >>
          timeout >> inode)) {
      continue;
    }
    const auto colon = local.rfind(':');
    if (colon == std::string::npos) continue;
    if (std::strtoul(local.c_str() + colon + 1, nullptr, 16) == port && inode != 0) {
      inodes.push_back(inode);
    }
  }
  return inodes;
}

std::vector<unsigned long> udp_socket_inodes(std::uint16_t port) {
  std::vector<unsigned long> inodes;
  for (const char* path : {"/proc/net/udp", "/proc/net/udp6"}) {
    std::ifstream file(path);
    const std::string table((std::istreambuf_iterator<char>(file)),
                            std::istreambuf_iterator<char>());
    const std::vector<unsigned long> found = udp_socket_inodes(table, port);
    inodes.insert(inodes.end(), found.begin(), found.end());
  }
  return inodes;
}

bool holds_socket(pid_t pid, const std::vector<unsigned long>& inodes) {
  const std::string dir_path = "/proc/" + std::to_string(pid) + "/fd";
  DIR* dir = ::opendir(dir_path.c_str());
  if (dir == nullptr) return false;
  bool holds = false;
  while (const dirent* entry = ::readdir(dir)) {
    char target[64];
    const std::string link = dir_path + "/" + entry->d_name;
    const ssize_t length = ::readlink(link.c_str(), target, sizeof(target) - 1);
    if (length <= 0) continue;
    const std::string text(target, static_cast<std::size_t>(length));
    // "socket:[12345]"
    if (text.rfind("socket:[", 0) != 0) continue;
    const unsigned long inode = std::strtoul(text.c_str() + 8, nullptr, 10);
    if (std::find(inodes.begin(), inodes.end(), inode) != inodes.end()) {
      holds = true;
      break;
    }
  }
  ::closedir(dir);
  return holds;
}

}  // namespace ubersim::ssl
