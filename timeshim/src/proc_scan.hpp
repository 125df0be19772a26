#pragma once
// What /proc says about the processes and threads of a shimmed group: their
// kernel state, how often they ran, the syscall they are blocked in, and
// whether the shim is loaded (docs/timeshim.md, "Quiescence").
#include <sys/types.h>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ubersim::timeshim {

struct ThreadSample {
  pid_t pid = 0;
  pid_t tid = 0;
  char state = '?';             // R, S, D, T, Z, ... (/proc/<pid>/task/<tid>/stat)
  std::uint64_t run_count = 0;  // times it was put on a CPU (schedstat)
};

struct SyscallSample {
  long number = -1;  // -1: not in a syscall; -2: running
  std::array<std::uint64_t, 6> args{};
};

// How a thread that sleeps in the kernel waits.
enum class KernelWait {
  ForOthers,  // for input or another thread, with no time limit: it waits for the group
  Timed,      // with a wall-time limit the shim did not turn into sim time
  Unknown,
};

// What the files of /proc/<pid>/task/<tid> say (ProcFiles reads them):
// `children` (pids, space-separated), `stat` and `schedstat`, `syscall`.
std::vector<pid_t> parse_pids(const std::string& text);
std::optional<ThreadSample> parse_thread_sample(pid_t pid, pid_t tid, const std::string& stat,
                                                const std::string& schedstat);
SyscallSample parse_syscall(const std::string& text);
KernelWait classify_wait(const SyscallSample& call);
std::string syscall_name(long number);
std::string comm_of(pid_t pid, pid_t tid);
std::string wchan_of(pid_t pid, pid_t tid);
std::string exe_of(pid_t pid);
// True when `pid`'s memory maps a file whose name contains `needle`.
bool maps_contain(pid_t pid, const std::string& needle);
// True when the ELF file has a PT_INTERP (is dynamically linked); nullopt when
// it is not an ELF file (a script: its interpreter is the one to check).
std::optional<bool> elf_is_dynamic(const std::string& path);
// Why the ELF file reads the clock without libc, where it can tell (a Go
// program: its runtime calls the vDSO itself, which LD_PRELOAD cannot
// reach), or "" when it sees no such sign.
std::string clock_without_libc(const std::string& path);

}  // namespace ubersim::timeshim
