// Reading /proc for the controller (proc_scan.hpp).
#include "proc_scan.hpp"

#include <elf.h>
#include <fcntl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>

namespace ubersim::timeshim {
namespace {

std::string task_path(pid_t pid, pid_t tid, const char* file) {
  return "/proc/" + std::to_string(pid) + "/task/" + std::to_string(tid) + "/" + file;
}

// POSIX reads, not ifstream: a file of a process that ends while it is read
// fails with ESRCH, which libstdc++'s filebuf turns into an exception.
std::optional<std::string> read_small_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  std::string text;
  char buffer[4096];
  for (;;) {
    const ssize_t got = ::read(fd, buffer, sizeof(buffer));
    if (got <= 0) {
      ::close(fd);
      if (got < 0) return std::nullopt;
      return text;
    }
    text.append(buffer, static_cast<std::size_t>(got));
  }
}

bool timeout_absent(std::uint64_t pointer) {
  return pointer == 0;
}
bool infinite_ms(std::uint64_t timeout) {
  return static_cast<int>(timeout) < 0;
}

}  // namespace

std::vector<pid_t> parse_pids(const std::string& text) {
  std::vector<pid_t> pids;
  std::istringstream in(text);
  pid_t pid = 0;
  while (in >> pid) pids.push_back(pid);
  return pids;
}

std::optional<ThreadSample> parse_thread_sample(pid_t pid, pid_t tid, const std::string& stat,
                                                const std::string& schedstat) {
  // "tid (comm) S ...": comm may hold spaces and parentheses; the state
  // follows the last ')'.
  const auto close = stat.rfind(')');
  if (close == std::string::npos || close + 2 >= stat.size()) return std::nullopt;
  ThreadSample sample;
  sample.pid = pid;
  sample.tid = tid;
  sample.state = stat[close + 2];
  std::istringstream fields(schedstat);
  std::uint64_t on_cpu_ns = 0, waited_ns = 0;
  fields >> on_cpu_ns >> waited_ns >> sample.run_count;
  return sample;
}

SyscallSample parse_syscall(const std::string& text) {
  SyscallSample sample;
  if (text.rfind("running", 0) == 0) {
    sample.number = -2;
    return sample;
  }
  std::istringstream in(text);
  in >> sample.number;
  for (auto& arg : sample.args) in >> std::hex >> arg;
  return sample;
}

KernelWait classify_wait(const SyscallSample& call) {
  const auto& a = call.args;
  switch (call.number) {
    case SYS_read:
    case SYS_readv:
    case SYS_recvfrom:
    case SYS_recvmsg:
    case SYS_accept:
    case SYS_accept4:
    case SYS_write:
    case SYS_writev:
    case SYS_sendto:
    case SYS_sendmsg:
    case SYS_connect:
    case SYS_wait4:
    case SYS_waitid:
    case SYS_pause:
    case SYS_rt_sigsuspend:
    case SYS_open:
    case SYS_openat:
    case SYS_flock:
    case SYS_msgrcv:
    case SYS_semop:
    case SYS_pread64:
    case SYS_preadv:
      return KernelWait::ForOthers;
    case SYS_futex:
      return timeout_absent(a[3]) ? KernelWait::ForOthers : KernelWait::Timed;
    case SYS_rt_sigtimedwait:
      return timeout_absent(a[2]) ? KernelWait::ForOthers : KernelWait::Timed;
    case SYS_poll:
      return infinite_ms(a[2]) ? KernelWait::ForOthers : KernelWait::Timed;
    case SYS_ppoll:
      return timeout_absent(a[2]) ? KernelWait::ForOthers : KernelWait::Timed;
    case SYS_select:
    case SYS_pselect6:
      return timeout_absent(a[4]) ? KernelWait::ForOthers : KernelWait::Timed;
    case SYS_epoll_wait:
    case SYS_epoll_pwait:
      return infinite_ms(a[3]) ? KernelWait::ForOthers : KernelWait::Timed;
    case SYS_epoll_pwait2:
      return timeout_absent(a[3]) ? KernelWait::ForOthers : KernelWait::Timed;
    case SYS_recvmmsg:
      return timeout_absent(a[4]) ? KernelWait::ForOthers : KernelWait::Timed;
    case SYS_nanosleep:
    case SYS_clock_nanosleep:
      return KernelWait::Timed;
    default:
      return KernelWait::Unknown;
  }
}

std::string syscall_name(long number) {
  switch (number) {
    case -2:
      return "no syscall (running)";
    case -1:
      return "no syscall (a fault or the scheduler)";
    case SYS_read:
      return "read";
    case SYS_readv:
      return "readv";
    case SYS_recvfrom:
      return "recvfrom";
    case SYS_recvmsg:
      return "recvmsg";
    case SYS_recvmmsg:
      return "recvmmsg";
    case SYS_accept:
      return "accept";
    case SYS_accept4:
      return "accept4";
    case SYS_write:
      return "write";
    case SYS_sendto:
      return "sendto";
    case SYS_connect:
      return "connect";
    case SYS_wait4:
      return "wait4";
    case SYS_waitid:
      return "waitid";
    case SYS_futex:
      return "futex";
    case SYS_poll:
      return "poll";
    case SYS_ppoll:
      return "ppoll";
    case SYS_select:
      return "select";
    case SYS_pselect6:
      return "pselect6";
    case SYS_epoll_wait:
      return "epoll_wait";
    case SYS_epoll_pwait:
      return "epoll_pwait";
    case SYS_epoll_pwait2:
      return "epoll_pwait2";
    case SYS_nanosleep:
      return "nanosleep";
    case SYS_clock_nanosleep:
      return "clock_nanosleep";
    case SYS_rt_sigtimedwait:
      return "rt_sigtimedwait";
    case SYS_timerfd_settime:
      return "timerfd_settime";
    default:
      return "syscall " + std::to_string(number);
  }
}

std::string comm_of(pid_t pid, pid_t tid) {
  std::string comm = read_small_file(task_path(pid, tid, "comm")).value_or("?");
  while (!comm.empty() && comm.back() == '\n') comm.pop_back();
  return comm;
}

std::string wchan_of(pid_t pid, pid_t tid) {
  return read_small_file(task_path(pid, tid, "wchan")).value_or("");
}

std::string exe_of(pid_t pid) {
  char target[4096];
  const std::string link = "/proc/" + std::to_string(pid) + "/exe";
  const ssize_t length = ::readlink(link.c_str(), target, sizeof(target) - 1);
  if (length <= 0) return "";
  return std::string(target, static_cast<std::size_t>(length));
}

bool maps_contain(pid_t pid, const std::string& needle) {
  const auto maps = read_small_file("/proc/" + std::to_string(pid) + "/maps");
  return maps && maps->find(needle) != std::string::npos;
}

std::optional<bool> elf_is_dynamic(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  Elf64_Ehdr header{};
  if (!file.read(reinterpret_cast<char*>(&header), sizeof(header))) return std::nullopt;
  if (std::string(reinterpret_cast<const char*>(header.e_ident), 4) != ELFMAG) return std::nullopt;
  if (header.e_ident[EI_CLASS] != ELFCLASS64) return true;  // not ours to judge
  for (int i = 0; i < header.e_phnum; ++i) {
    Elf64_Phdr program{};
    file.seekg(static_cast<std::streamoff>(header.e_phoff +
                                           static_cast<std::uint64_t>(i) * header.e_phentsize));
    if (!file.read(reinterpret_cast<char*>(&program), sizeof(program))) return false;
    if (program.p_type == PT_INTERP) return true;
  }
  return false;
}

namespace {

// The names of the ELF file's sections (empty when it has none or is not ELF64).
std::vector<std::string> section_names(std::ifstream& file, const Elf64_Ehdr& header) {
  std::vector<std::string> names;
  if (header.e_shoff == 0 || header.e_shstrndx >= header.e_shnum) return names;
  std::vector<Elf64_Shdr> sections(header.e_shnum);
  file.seekg(static_cast<std::streamoff>(header.e_shoff));
  if (!file.read(reinterpret_cast<char*>(sections.data()),
                 static_cast<std::streamsize>(sections.size() * sizeof(Elf64_Shdr)))) {
    return names;
  }
  const Elf64_Shdr& strings = sections[header.e_shstrndx];
  if (strings.sh_size > (1U << 24)) return names;
  std::string table(strings.sh_size, '\0');
  file.seekg(static_cast<std::streamoff>(strings.sh_offset));
  if (!file.read(table.data(), static_cast<std::streamsize>(table.size()))) return names;
  for (const auto& section : sections) {
    if (section.sh_name < table.size()) names.emplace_back(table.c_str() + section.sh_name);
  }
  return names;
}

}  // namespace

std::string clock_without_libc(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  Elf64_Ehdr header{};
  if (!file.read(reinterpret_cast<char*>(&header), sizeof(header))) return "";
  if (std::string(reinterpret_cast<const char*>(header.e_ident), 4) != ELFMAG ||
      header.e_ident[EI_CLASS] != ELFCLASS64) {
    return "";
  }
  for (const std::string& name : section_names(file, header)) {
    if (name == ".go.buildinfo" || name == ".gopclntab" || name == ".note.go.buildid") {
      return "it is a Go program (section " + name +
             "): the Go runtime reads the clock from the vDSO and sleeps with raw system calls, "
             "not through libc, so LD_PRELOAD cannot give it sim time";
    }
  }
  return "";
}

}  // namespace ubersim::timeshim
