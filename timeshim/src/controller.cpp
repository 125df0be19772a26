// The controller's segment, process start and time (controller.hpp).
#include "ubersim/timeshim/controller.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/personality.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <new>
#include <thread>

#include "proc_files.hpp"
#include "proc_scan.hpp"

extern char** environ;

namespace ubersim::timeshim {

// The shared segment: a file in segment_dir, mapped, removed with the controller.
class Controller::Segment {
 public:
  explicit Segment(const std::string& dir) {
    static int counter = 0;
    path_ =
        dir + "/ubersim-timeshim-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0)
      throw std::runtime_error("timeshim: cannot create " + path_ + ": " + std::strerror(errno));
    if (::ftruncate(fd, sizeof(Header)) != 0) {
      ::close(fd);
      ::unlink(path_.c_str());
      throw std::runtime_error("timeshim: cannot size " + path_);
    }
    void* mapped = ::mmap(nullptr, sizeof(Header), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    ::close(fd);
    if (mapped == MAP_FAILED) {
      ::unlink(path_.c_str());
      throw std::runtime_error("timeshim: cannot map " + path_);
    }
    header_ = new (mapped) Header();
  }
  ~Segment() {
    ::munmap(header_, sizeof(Header));
    ::unlink(path_.c_str());
  }
  Segment(const Segment&) = delete;
  Segment& operator=(const Segment&) = delete;
  Header& header() { return *header_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  Header* header_ = nullptr;
};

namespace {

std::string choose_segment_dir(const std::string& wanted) {
  if (!wanted.empty()) return wanted;
  const char* tmp = std::getenv("TMPDIR");
  if (tmp != nullptr && *tmp != '\0') return tmp;
  return ::access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
}

std::string find_in_path(const std::string& program) {
  if (program.find('/') != std::string::npos) return program;
  const char* path_env = std::getenv("PATH");
  std::string paths = path_env != nullptr ? path_env : "/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= paths.size()) {
    const std::size_t end = std::min(paths.find(':', start), paths.size());
    const std::string candidate = paths.substr(start, end - start) + "/" + program;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
    start = end + 1;
  }
  return program;
}

bool starts_with(const char* text, const std::string& prefix) {
  return std::strncmp(text, prefix.c_str(), prefix.size()) == 0;
}

}  // namespace

std::string default_shim_library() {
  if (const char* given = std::getenv("UBERSIM_TIMESHIM_LIB"); given != nullptr && *given != '\0') {
    return given;
  }
  char self[4096];
  const ssize_t length = ::readlink("/proc/self/exe", self, sizeof(self) - 1);
  std::string dir = length > 0 ? std::string(self, static_cast<std::size_t>(length)) : "";
  dir = dir.substr(0, dir.rfind('/'));
  return dir + "/../lib/libubersim_timeshim.so";
}

Controller::Controller(ControllerOptions options)
    : options_(std::move(options)),
      segment_(std::make_unique<Segment>(choose_segment_dir(options_.segment_dir))),
      proc_(std::make_unique<ProcFiles>()),
      shim_library_(options_.shim_library.empty() ? default_shim_library()
                                                  : options_.shim_library) {
  if (::access(shim_library_.c_str(), R_OK) != 0) {
    throw std::runtime_error("timeshim: no shim library at " + shim_library_);
  }
  Header& header = segment_->header();
  header.realtime_epoch_ns = options_.realtime_epoch_ns;
  header.charge_ns = options_.charge_ns;
  header.yield_after_ns = options_.yield_after_ns;
  header.wake_signal = SIGRTMAX - 1;
  header.deterministic = options_.deterministic ? 1 : 0;
  header.controller_pid = ::getpid();
  header.size = sizeof(Header);
  header.version = kVersion;
  header.magic = kMagic;  // last: a process that sees it sees the rest
}

// What is left of the processes it started goes with their time: nothing
// could wake them any more.
Controller::~Controller() {
  proc_->new_look();
  std::vector<pid_t> pending;
  for (pid_t root : roots_) {
    if (exit_status_.count(root) == 0) pending.push_back(root);
  }
  while (!pending.empty()) {
    const pid_t pid = pending.back();
    pending.pop_back();
    for (pid_t child : proc_->children_of(pid)) pending.push_back(child);
    ::kill(pid, SIGKILL);
  }
  reap(true);
}

Header& Controller::header() {
  return segment_->header();
}

std::vector<std::string> Controller::environment() const {
  std::string preload = shim_library_;
  if (const char* old = std::getenv("LD_PRELOAD"); old != nullptr && *old != '\0') {
    preload += std::string(":") + old;
  }
  return {"LD_PRELOAD=" + preload, std::string(kSegmentEnv) + "=" + segment_->path()};
}

pid_t Controller::spawn(const std::vector<std::string>& argv, const std::string& output_path) {
  if (argv.empty()) throw std::invalid_argument("timeshim: spawn needs a program");
  const std::string program = find_in_path(argv[0]);
  if (elf_is_dynamic(program) == false) {
    throw UnsupportedProgram(program +
                             " is statically linked: LD_PRELOAD cannot load the time shim into it, "
                             "so it would run on wall time");
  }
  if (const std::string why = clock_without_libc(program); !why.empty()) {
    throw UnsupportedProgram(program + " would run on wall time under the time shim: " + why);
  }
  std::vector<std::string> env_strings = environment();
  for (char** entry = environ; *entry != nullptr; ++entry) {
    if (!starts_with(*entry, "LD_PRELOAD=") &&
        !starts_with(*entry, std::string(kSegmentEnv) + "=")) {
      env_strings.emplace_back(*entry);
    }
  }
  // Deterministic mode: CPython's string hashes (the order of a set of str)
  // the same on every run, as addresses below, unless the caller chose a seed.
  if (options_.deterministic && std::getenv("PYTHONHASHSEED") == nullptr) {
    env_strings.emplace_back("PYTHONHASHSEED=0");
  }
  std::vector<char*> envp;
  envp.reserve(env_strings.size() + 1);
  for (auto& entry : env_strings) envp.push_back(entry.data());
  envp.push_back(nullptr);
  std::vector<std::string> arg_strings = argv;
  std::vector<char*> args;
  args.reserve(arg_strings.size() + 1);
  for (auto& arg : arg_strings) args.push_back(arg.data());
  args.push_back(nullptr);
  int output = -1;
  if (!output_path.empty()) {
    output = ::open(output_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (output < 0) throw std::runtime_error("timeshim: cannot write " + output_path);
  }
  const std::string exec_failed = "timeshim: cannot execute " + program + "\n";
  const pid_t pid = ::fork();
  if (pid == 0) {
    // Deterministic mode: the same addresses on every run (what a program
    // orders by address, a CPython set of objects, then orders alike).
    if (options_.deterministic) ::personality(ADDR_NO_RANDOMIZE);
    if (output >= 0) {
      ::dup2(output, 1);
      ::dup2(output, 2);
    }
    ::execve(program.c_str(), args.data(), envp.data());
    if (::write(2, exec_failed.data(), exec_failed.size()) < 0) ::_exit(127);
    ::_exit(127);
  }
  if (output >= 0) ::close(output);
  if (pid < 0) throw std::runtime_error("timeshim: fork failed");
  roots_.push_back(pid);
  return pid;
}

std::int64_t Controller::now_ns() const {
  return segment_->header().sim_now_ns.load();
}

std::uint64_t Controller::intercepted_calls() const {
  return segment_->header().intercepted_calls.load();
}

std::uint64_t Controller::charged_pauses() const {
  return segment_->header().charged_pauses.load();
}

void Controller::advance_to(std::int64_t sim_ns) {
  Header& header = segment_->header();
  if (sim_ns <= header.sim_now_ns.load()) return;
  header.sim_now_ns.store(sim_ns);
  ++advances_;
  wake_due();
}

void Controller::wake_due() {
  Header& header = segment_->header();
  const std::int64_t now = header.sim_now_ns.load();
  std::map<pid_t, ThreadSlot*> helpers;  // by process: wakes its condition variable waiters
  for (auto& slot : used_slots(header)) {
    if (slot.claim.load() != 0 &&
        slot.state.load() == static_cast<std::uint32_t>(ThreadState::Helper)) {
      helpers[slot.pid.load()] = &slot;
    }
  }
  for (auto& slot : used_slots(header)) {
    if (slot.claim.load() == 0 || slot.deadline_ns.load() > now) continue;
    const auto state = static_cast<ThreadState>(slot.state.load());
    if (state == ThreadState::DetBlocked) {
      // Its deadline passed: it wants its turn (and sees no peer ended its wait).
      auto blocked = static_cast<std::uint32_t>(ThreadState::DetBlocked);
      slot.state.compare_exchange_strong(blocked,
                                         static_cast<std::uint32_t>(ThreadState::WantToken));
      continue;
    }
    ThreadSlot* to_wake = &slot;
    if (state == ThreadState::WaitingCond || state == ThreadState::Timer) {
      const auto helper = helpers.find(slot.pid.load());
      if (helper == helpers.end()) continue;  // not started yet: woken at the next look
      to_wake = helper->second;
    }
    light_.woken.insert(to_wake->tid.load());  // it runs now: a light look reads it
    if (state == ThreadState::Sleeping || state == ThreadState::WaitingCond ||
        state == ThreadState::Timer) {
      to_wake->wake_seq.fetch_add(1);
      futex_wake_all(to_wake->wake_seq);
    } else if (state == ThreadState::WaitingFd || state == ThreadState::WaitingSem) {
      ::syscall(SYS_tgkill, slot.pid.load(), slot.tid.load(), header.wake_signal);
    }
  }
}

Quiescence Controller::run_until(std::int64_t until_ns, std::chrono::milliseconds wall_limit) {
  const auto give_up = std::chrono::steady_clock::now() + wall_limit;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        give_up - std::chrono::steady_clock::now());
    Quiescence q = wait_quiescent(std::max(left, std::chrono::milliseconds(0)));
    if (q.state != GroupState::Quiescent) return q;
    if (q.next_deadline_ns != kNoDeadline && q.next_deadline_ns <= until_ns) {
      advance_to(q.next_deadline_ns);
      continue;
    }
    if (until_ns != kNoDeadline) advance_to(until_ns);
    return q;
  }
}

void Controller::reap(bool wait_for_end) {
  for (pid_t pid : roots_) {
    if (exit_status_.count(pid) != 0) continue;
    int status = 0;
    if (::waitpid(pid, &status, wait_for_end ? 0 : WNOHANG) == pid) {
      exit_status_[pid] = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
  }
}

std::optional<int> Controller::exit_status(pid_t pid) const {
  const auto found = exit_status_.find(pid);
  if (found == exit_status_.end()) return std::nullopt;
  return found->second;
}

std::vector<Problem> Controller::take_problems() {
  std::vector<Problem> taken;
  taken.swap(problems_);
  return taken;
}

}  // namespace ubersim::timeshim
