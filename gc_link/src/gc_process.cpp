#include "ubersim/gc_link/gc_process.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <thread>
#include <vector>

namespace ubersim::gc_link {
namespace {

std::string go_duration(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0fms", seconds * 1000);
  return text;
}

}  // namespace

int free_local_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) throw std::runtime_error("cannot open a socket to find a free port");
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = 0;
  socklen_t size = sizeof address;
  const bool ok = ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0 &&
                  ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size) == 0;
  ::close(fd);
  if (!ok) throw std::runtime_error("cannot find a free TCP port on 127.0.0.1");
  return ntohs(address.sin_port);
}

std::string gc_config_yaml(const GcGame& game) {
  const std::string division = game.division_a ? "DIV_A" : "DIV_B";
  return "# Written by ubersim_gc_link for one game (docs/official_gc.md).\n"
         "time-acquisition-mode: ci\n"
         "network:\n"
         "  publish-address: \"\"\n"  // ubersim sends the Referee, stamped with sim time
         "  vision-address: \"\"\n"
         "  tracker-address: \"\"\n"
         "server:\n"
         "  auto-ref:\n    address: 127.0.0.1:0\n"
         "  team:\n    address: 127.0.0.1:0\n"
         "  remote-control:\n    address: 127.0.0.1:0\n"
         "game:\n"
         "  default-division: " +
         division +
         "\n"
         "  auto-approve-goals: true\n"  // no human to approve them
         "  preparation-time-after-halt: 2s\n"
         "  normal:\n"
         "    half-duration: " +
         go_duration(game.half_duration) +
         "\n"
         "    half-time-duration: " +
         go_duration(game.half_time_duration) + "\n";
}

GcProcess::GcProcess(const std::string& binary, const std::string& folder, const GcGame& game) {
  namespace fs = std::filesystem;
  if (::access(binary.c_str(), X_OK) != 0) {
    throw std::runtime_error("the game controller '" + binary + "' is not an executable file");
  }
  fs::create_directories(fs::path(folder) / "config");
  {
    std::ofstream config(fs::path(folder) / "config" / "ssl-game-controller.yaml");
    config << gc_config_yaml(game);
    if (!config) throw std::runtime_error("cannot write the game controller's config in " + folder);
  }
  port_ = free_local_port();
  const std::string address = ci_address();
  const std::string log = (fs::path(folder) / "gc.log").string();
  const std::string absolute = fs::absolute(binary).string();
  std::vector<std::string> args = {absolute, "-timeAcquisitionMode", "ci", "-ciAddress",
                                   address,  "-backendOnly"};
  // Built before fork: the child of a threaded process should not allocate before execv.
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_ = ::fork();
  if (pid_ < 0) throw std::runtime_error("cannot start the game controller (fork failed)");
  if (pid_ == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);  // never outlives the link
    const int out = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out >= 0) {
      ::dup2(out, 1);
      ::dup2(out, 2);
    }
    if (::chdir(folder.c_str()) != 0) ::_exit(127);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
}

bool GcProcess::running() {
  if (pid_ <= 0) return false;
  int status = 0;
  if (::waitpid(pid_, &status, WNOHANG) == pid_) {
    pid_ = -1;
    return false;
  }
  return true;
}

GcProcess::~GcProcess() {
  if (!running()) return;
  ::kill(pid_, SIGTERM);
  for (int i = 0; i < 50; ++i) {  // up to 2.5 s to save its state store and quit
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ::kill(pid_, SIGKILL);
  ::waitpid(pid_, nullptr, 0);
}

}  // namespace ubersim::gc_link
