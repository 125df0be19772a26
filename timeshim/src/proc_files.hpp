#pragma once
// The /proc files the controller reads at every look, kept open and read
// again from their start (pread): a look then opens and closes nothing it
// read before. Opening and closing were half of a look's cost, and looks are
// what the controller spends its time on (two per quiescence, one per turn in
// deterministic mode).
#include <dirent.h>
#include <sys/types.h>

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "proc_scan.hpp"

namespace ubersim::timeshim {

// The run count of each thread of a process, read while every one of them
// slept (kNotRead for a thread a look did not read: deterministic mode's
// waiters, which run only in a turn the controller gives).
using RunCounts = std::map<pid_t, std::uint64_t>;
constexpr std::uint64_t kNotRead = ~std::uint64_t{0};

// An open file descriptor, closed with its owner.
class UniqueFd {
 public:
  UniqueFd() = default;
  explicit UniqueFd(int fd) : fd_(fd) {}
  UniqueFd(UniqueFd&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  UniqueFd& operator=(UniqueFd&& other) noexcept;
  UniqueFd(const UniqueFd&) = delete;
  UniqueFd& operator=(const UniqueFd&) = delete;
  ~UniqueFd();
  int get() const { return fd_; }
  bool valid() const { return fd_ >= 0; }
  void reset();

 private:
  int fd_ = -1;
};

class ProcFiles {
 public:
  // The same as the free functions of proc_scan.hpp, from open files.
  std::vector<pid_t> threads_of(pid_t pid);
  std::vector<pid_t> children_of(pid_t pid);
  // The same, unless `asleep` (the run counts of pid's threads, read before
  // this call) equals those read before an earlier call: then no thread of
  // pid was put on a CPU since, none can have forked, and that call's answer
  // stands (a child that ended since is still in it: callers check). About
  // one read per thread saved at most looks; a look reads many threads.
  std::vector<pid_t> children_of(pid_t pid, const std::optional<RunCounts>& asleep);
  // A thread of pid is about to run unread (deterministic mode's turn).
  void forget_children(pid_t pid) { children_.erase(pid); }
  std::optional<ThreadSample> sample_thread(pid_t pid, pid_t tid);
  std::optional<SyscallSample> sample_syscall(pid_t pid, pid_t tid);
  // Only the kernel state (R, S, ...) of the thread; nullopt when it is gone.
  std::optional<char> state_of(pid_t pid, pid_t tid);
  // The write calls the kernel counted for the thread (/proc/.../io's syscw:
  // write, writev, pwrite and the like, libc's own included); nullopt when
  // it is gone or the file cannot be read.
  std::optional<std::uint64_t> writes_of(pid_t pid, pid_t tid);
  // The pid the kernel gave out last, to a thread or process of any program
  // (/proc/loadavg): while it stays the same, no thread was created.
  std::optional<long> last_pid();
  // Whether a kernel softirq thread (ksoftirqd/N) is runnable. A datagram
  // sent over loopback is put into its receiver's socket, and wakes the
  // receiver, in the sender's system call, unless the kernel defers that
  // work to ksoftirqd (under load): then until ksoftirqd has run, the
  // receiver sleeps with its input on the way. False where the kernel's
  // threads are not visible (another pid namespace).
  bool softirq_work_pending();
  // A new look: threads_of lists each process's threads again (within a look,
  // once: the group's discovery and the look itself both ask).
  void new_look() { listed_.clear(); }
  // Closes the files of every process and thread not in these sets.
  void keep_only(const std::set<pid_t>& pids, const std::set<pid_t>& tids);

 private:
  enum File { kStat, kSchedstat, kSyscall, kChildren, kIo, kFiles };
  // The text of `file` of thread tid of pid, read now; nullopt when it is gone.
  std::optional<std::string> read(pid_t pid, pid_t tid, File file);

  using ThreadKey = std::pair<pid_t, pid_t>;  // pid, tid: a tid may come back in another process
  struct DirCloser {
    void operator()(DIR* dir) const { ::closedir(dir); }
  };
  std::map<ThreadKey, std::array<UniqueFd, kFiles>> threads_;
  std::map<pid_t, std::unique_ptr<DIR, DirCloser>> task_dirs_;  // /proc/<pid>/task
  std::map<pid_t, std::vector<pid_t>> listed_;                  // this look's threads_of
  struct ChildrenSeen {
    RunCounts asleep;  // read before the children were
    std::vector<pid_t> children;
  };
  std::map<pid_t, ChildrenSeen> children_;
  UniqueFd loadavg_;
  std::optional<std::vector<UniqueFd>> softirq_threads_;  // their stat files, found once
};

}  // namespace ubersim::timeshim
