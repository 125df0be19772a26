// The controller's open /proc files (proc_files.hpp).
#include "proc_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cstdlib>
#include <memory>
#include <string>

namespace ubersim::timeshim {
namespace {

constexpr const char* kFileNames[] = {"stat", "schedstat", "syscall", "children", "io"};

// A read that leaves this much of the buffer unused got the whole file: a
// /proc file is a seq_file, whose read stops short only at its end or where
// its next record (a line, a pid of "children": far shorter than this) would
// not fit its own page-sized buffer.
constexpr ssize_t kRoomForARecord = 512;

// The whole file, from its start: /proc regenerates it for a read at offset
// 0. Read until a short read, not until a read of 0: a read past the start
// regenerates the whole file again (seq_file's traverse) to find nothing, and
// would double what a look costs.
std::optional<std::string> read_from_start(int fd) {
  std::string text;
  char buffer[4096];
  for (off_t offset = 0;;) {
    const ssize_t got = ::pread(fd, buffer, sizeof(buffer), offset);
    if (got < 0) return std::nullopt;  // ESRCH: the thread is gone
    text.append(buffer, static_cast<std::size_t>(got));
    if (got + kRoomForARecord <= static_cast<ssize_t>(sizeof(buffer))) return text;
    offset += got;
  }
}

}  // namespace

UniqueFd& UniqueFd::operator=(UniqueFd&& other) noexcept {
  if (this != &other) {
    reset();
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

UniqueFd::~UniqueFd() {
  reset();
}

void UniqueFd::reset() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

std::optional<std::string> ProcFiles::read(pid_t pid, pid_t tid, File file) {
  UniqueFd& fd = threads_[{pid, tid}][file];
  // A file kept open may belong to a thread that ended (its tid since given
  // to another): opened afresh once when it cannot be read.
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (!fd.valid()) {
      const std::string path =
          "/proc/" + std::to_string(pid) + "/task/" + std::to_string(tid) + "/" + kFileNames[file];
      fd = UniqueFd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
      if (!fd.valid()) return std::nullopt;
    }
    if (auto text = read_from_start(fd.get())) return text;
    fd.reset();
  }
  return std::nullopt;
}

std::vector<pid_t> ProcFiles::threads_of(pid_t pid) {
  if (const auto listed = listed_.find(pid); listed != listed_.end()) return listed->second;
  std::vector<pid_t>& tids = listed_[pid];
  auto& dir = task_dirs_[pid];
  if (dir) {
    ::rewinddir(dir.get());  // the next read lists the threads of now
  } else {
    dir.reset(::opendir(("/proc/" + std::to_string(pid) + "/task").c_str()));
    if (!dir) return tids;
  }
  while (const dirent* entry = ::readdir(dir.get())) {
    char* end = nullptr;
    const long value = std::strtol(entry->d_name, &end, 10);
    if (end != entry->d_name && *end == '\0') tids.push_back(static_cast<pid_t>(value));
  }
  if (tids.empty()) task_dirs_.erase(pid);  // gone (or a pid given to another since)
  return tids;
}

std::vector<pid_t> ProcFiles::children_of(pid_t pid) {
  std::vector<pid_t> children;
  for (pid_t tid : threads_of(pid)) {
    const std::vector<pid_t> more = parse_pids(read(pid, tid, kChildren).value_or(""));
    children.insert(children.end(), more.begin(), more.end());
  }
  return children;
}

std::vector<pid_t> ProcFiles::children_of(pid_t pid, const std::optional<RunCounts>& asleep) {
  if (!asleep) {
    children_.erase(pid);
    return children_of(pid);
  }
  const auto seen = children_.find(pid);
  if (seen != children_.end() && seen->second.asleep == *asleep) return seen->second.children;
  ChildrenSeen& fresh = children_[pid];
  fresh = ChildrenSeen{*asleep, children_of(pid)};
  return fresh.children;
}

std::optional<ThreadSample> ProcFiles::sample_thread(pid_t pid, pid_t tid) {
  const auto stat = read(pid, tid, kStat);
  const auto schedstat = read(pid, tid, kSchedstat);
  if (!stat || !schedstat) return std::nullopt;
  return parse_thread_sample(pid, tid, *stat, *schedstat);
}

std::optional<char> ProcFiles::state_of(pid_t pid, pid_t tid) {
  const auto stat = read(pid, tid, kStat);
  if (!stat) return std::nullopt;
  const auto sample = parse_thread_sample(pid, tid, *stat, "");
  if (!sample) return std::nullopt;
  return sample->state;
}

std::optional<std::uint64_t> ProcFiles::writes_of(pid_t pid, pid_t tid) {
  const auto text = read(pid, tid, kIo);
  constexpr const char* kField = "syscw: ";
  const auto field = text ? text->find(kField) : std::string::npos;
  if (field == std::string::npos) return std::nullopt;
  const char* digits = text->c_str() + field + std::char_traits<char>::length(kField);
  char* end = nullptr;
  const unsigned long long count = std::strtoull(digits, &end, 10);
  if (end == digits) return std::nullopt;
  return count;
}

std::optional<SyscallSample> ProcFiles::sample_syscall(pid_t pid, pid_t tid) {
  const auto text = read(pid, tid, kSyscall);
  if (!text) return std::nullopt;
  return parse_syscall(*text);
}

std::optional<long> ProcFiles::last_pid() {
  if (!loadavg_.valid()) loadavg_ = UniqueFd(::open("/proc/loadavg", O_RDONLY | O_CLOEXEC));
  const auto text = loadavg_.valid() ? read_from_start(loadavg_.get()) : std::nullopt;
  // "0.20 0.18 0.12 1/80 11206": the last field.
  const auto space = text ? text->find_last_of(' ') : std::string::npos;
  if (space == std::string::npos) return std::nullopt;
  char* end = nullptr;
  const long pid = std::strtol(text->c_str() + space + 1, &end, 10);
  if (end == text->c_str() + space + 1) return std::nullopt;
  return pid;
}

namespace {

// The stat files of the kernel's ksoftirqd/N threads (children of kthreadd).
std::vector<UniqueFd> open_softirq_threads() {
  std::vector<UniqueFd> found;
  const std::unique_ptr<DIR, int (*)(DIR*)> proc(::opendir("/proc"), ::closedir);
  if (!proc) return found;
  while (const dirent* entry = ::readdir(proc.get())) {
    const std::string dir = std::string("/proc/") + entry->d_name;
    if (entry->d_name[0] < '1' || entry->d_name[0] > '9') continue;
    UniqueFd stat(::open((dir + "/stat").c_str(), O_RDONLY | O_CLOEXEC));
    const auto text = stat.valid() ? read_from_start(stat.get()) : std::nullopt;
    // "14 (ksoftirqd/0) S 2 ...": the comm, then state and parent.
    const auto close = text ? text->rfind(')') : std::string::npos;
    if (close != std::string::npos && text->find(" (ksoftirqd/") != std::string::npos &&
        text->compare(close + 3, 3, " 2 ") == 0) {
      found.push_back(std::move(stat));
    }
  }
  return found;
}

}  // namespace

bool ProcFiles::softirq_work_pending() {
  if (!softirq_threads_) softirq_threads_ = open_softirq_threads();
  for (const UniqueFd& stat : *softirq_threads_) {
    const auto text = read_from_start(stat.get());
    const auto close = text ? text->rfind(')') : std::string::npos;
    if (close != std::string::npos && close + 2 < text->size() && (*text)[close + 2] == 'R') {
      return true;
    }
  }
  return false;
}

void ProcFiles::keep_only(const std::set<pid_t>& pids, const std::set<pid_t>& tids) {
  for (auto it = threads_.begin(); it != threads_.end();) {
    const bool kept = pids.count(it->first.first) != 0 && tids.count(it->first.second) != 0;
    it = kept ? std::next(it) : threads_.erase(it);
  }
  for (auto it = task_dirs_.begin(); it != task_dirs_.end();) {
    it = pids.count(it->first) != 0 ? std::next(it) : task_dirs_.erase(it);
  }
  for (auto it = children_.begin(); it != children_.end();) {
    it = pids.count(it->first) != 0 ? std::next(it) : children_.erase(it);
  }
}

}  // namespace ubersim::timeshim
