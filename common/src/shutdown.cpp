#include "ubersim/shutdown.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <stdexcept>

namespace ubersim {
namespace {

std::atomic<bool> g_requested{false};
std::atomic<int> g_signal{0};
int g_pipe[2] = {-1, -1};
bool g_installed = false;
struct sigaction g_old_int {};
struct sigaction g_old_term {};

void on_signal(int signal_number) {
  g_signal = signal_number;
  g_requested = true;
  const char byte = 1;
  // write() is async-signal-safe; a full pipe already means "readable".
  [[maybe_unused]] auto ignored = ::write(g_pipe[1], &byte, 1);
}

}  // namespace

ShutdownSignal::ShutdownSignal() {
  if (g_installed) throw std::logic_error("only one ShutdownSignal per process");
  if (::pipe2(g_pipe, O_NONBLOCK | O_CLOEXEC) != 0) throw std::runtime_error("pipe2 failed");
  g_requested = false;
  g_signal = 0;
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, &g_old_int);
  sigaction(SIGTERM, &action, &g_old_term);
  g_installed = true;
}

ShutdownSignal::~ShutdownSignal() {
  sigaction(SIGINT, &g_old_int, nullptr);
  sigaction(SIGTERM, &g_old_term, nullptr);
  ::close(g_pipe[0]);
  ::close(g_pipe[1]);
  g_pipe[0] = g_pipe[1] = -1;
  g_installed = false;
}

bool ShutdownSignal::requested() const {
  return g_requested;
}
int ShutdownSignal::fd() const {
  return g_pipe[0];
}
int ShutdownSignal::signal_number() const {
  return g_signal;
}
void ShutdownSignal::request() {
  on_signal(0);
}

}  // namespace ubersim
