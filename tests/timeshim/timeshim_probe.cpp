// A team-like program for the time shim's tests (test_timeshim.cpp): each
// mode does one thing the shim must handle and prints the sim times it saw,
// one "label seconds" line each, so that a test can check them and compare
// two runs.
#include <arpa/inet.h>
#include <linux/futex.h>
#include <netinet/in.h>
#include <poll.h>
#include <pthread.h>
#include <semaphore.h>
#include <sys/epoll.h>
#include <sys/select.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <sys/time.h>
#include <sys/timerfd.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace {

double monotonic_s() {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<double>(now.tv_sec) + static_cast<double>(now.tv_nsec) * 1e-9;
}

void say(const char* label, double value) {
  std::printf("%s %.9f\n", label, value);
  std::fflush(stdout);
}

int sleeps() {
  say("start", monotonic_s());
  timespec second{1, 0};
  nanosleep(&second, nullptr);
  say("nanosleep", monotonic_s());
  usleep(500000);
  say("usleep", monotonic_s());
  sleep(2);
  say("sleep", monotonic_s());
  timespec deadline{};
  clock_gettime(CLOCK_MONOTONIC, &deadline);
  deadline.tv_sec += 3;
  clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &deadline, nullptr);
  say("clock_nanosleep_abs", monotonic_s());
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  say("sleep_for", monotonic_s());
  say("steady_clock",
      std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count());
  timeval wall{};
  gettimeofday(&wall, nullptr);
  say("gettimeofday", static_cast<double>(wall.tv_sec) + static_cast<double>(wall.tv_usec) * 1e-6);
  say("time", static_cast<double>(time(nullptr)));
  say("system_clock",
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count());
  return 0;
}

int fd_timeouts() {
  int fds[2];
  if (pipe(fds) != 0) return 1;
  say("start", monotonic_s());
  fd_set readable;
  FD_ZERO(&readable);
  FD_SET(fds[0], &readable);
  timeval timeout{0, 250000};
  const int selected = select(fds[0] + 1, &readable, nullptr, nullptr, &timeout);
  say("select", monotonic_s());
  pollfd wanted{fds[0], POLLIN, 0};
  const int polled = poll(&wanted, 1, 750);
  say("poll", monotonic_s());
  const int epoll = epoll_create1(0);
  epoll_event event{};
  event.events = EPOLLIN;
  event.data.fd = fds[0];
  epoll_ctl(epoll, EPOLL_CTL_ADD, fds[0], &event);
  epoll_event got[1];
  const int waited = epoll_wait(epoll, got, 1, 2000);
  say("epoll_wait", monotonic_s());
  // Readiness before the deadline: a thread writes after 100 ms of sim time.
  std::thread writer([&] {
    usleep(100000);
    if (write(fds[1], "x", 1) != 1) std::perror("write");
  });
  const int ready = poll(&wanted, 1, 5000);
  say("poll_ready", monotonic_s());
  writer.join();
  say("results", selected * 1000 + polled * 100 + waited * 10 + ready);
  return 0;
}

int threads() {
  std::map<int, std::vector<double>> seen;
  std::vector<std::thread> workers;
  for (int worker = 1; worker <= 3; ++worker) {
    // The entry is made here, not in the worker: three threads inserting into
    // one map at once race (a lost entry dropped a worker's lines).
    std::vector<double>& mine = seen[worker];
    workers.emplace_back([worker, &mine] {
      for (int i = 0; i < 4; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(100 * worker));
        mine.push_back(monotonic_s());
      }
    });
  }
  for (auto& worker : workers) worker.join();
  for (const auto& [worker, times] : seen) {
    for (double t : times) say(("thread" + std::to_string(worker)).c_str(), t);
  }
  say("end", monotonic_s());
  return 0;
}

int forks() {
  const pid_t child = fork();
  if (child == 0) {
    sleep(2);
    say("child", monotonic_s());
    _exit(0);
  }
  usleep(500000);
  say("parent", monotonic_s());
  int status = 0;
  waitpid(child, &status, 0);
  say("reaped", monotonic_s());
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

// A UDP socket on the loopback, its port written to *port.
int bound_socket(int* port) {
  const int sock = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (bind(sock, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) return -1;
  socklen_t length = sizeof(address);
  getsockname(sock, reinterpret_cast<sockaddr*>(&address), &length);
  *port = ntohs(address.sin_port);
  return sock;
}

// Every thread waits on a socket of its own with no deadline: one in poll(),
// one in a plain blocking recv(). Quiescent until datagrams come from outside
// the group.
int socket_wait() {
  int poll_port = 0, recv_port = 0;
  const int polled = bound_socket(&poll_port);
  const int received = bound_socket(&recv_port);
  if (polled < 0 || received < 0) return 1;
  std::printf("ports %d %d\n", poll_port, recv_port);
  std::fflush(stdout);
  std::thread reader([received] {
    char buffer[64];
    const ssize_t got = recv(received, buffer, sizeof(buffer), 0);  // no shim call
    say("received", static_cast<double>(got));
  });
  pollfd wanted{polled, POLLIN, 0};
  poll(&wanted, 1, -1);
  say("poll_woke", monotonic_s());
  reader.join();
  return 0;
}

// A receive timeout set with SO_RCVTIMEO ends in sim time.
int receive_timeout() {
  int port = 0;
  const int sock = bound_socket(&port);
  const timeval timeout{1, 500000};
  setsockopt(sock, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
  char buffer[16];
  const ssize_t got = recv(sock, buffer, sizeof(buffer), 0);
  say("recv_timed_out", got < 0 && errno == EAGAIN ? monotonic_s() : -1.0);
  const ssize_t read_got = read(sock, buffer, sizeof(buffer));
  say("read_timed_out", read_got < 0 && errno == EAGAIN ? monotonic_s() : -1.0);
  timeval seen{};
  socklen_t length = sizeof(seen);
  getsockopt(sock, SOL_SOCKET, SO_RCVTIMEO, &seen, &length);
  say("timeout", static_cast<double>(seen.tv_sec) + static_cast<double>(seen.tv_usec) * 1e-6);
  return 0;
}

// A periodic timerfd (first expiry at 0.5 s, then every 0.25 s), read with
// a blocking read and through epoll.
int timer_fd() {
  const int timer = timerfd_create(CLOCK_MONOTONIC, TFD_CLOEXEC);
  itimerspec every{};
  every.it_value.tv_nsec = 500000000;
  every.it_interval.tv_nsec = 250000000;
  timerfd_settime(timer, 0, &every, nullptr);
  std::uint64_t expirations = 0;
  for (int i = 0; i < 3; ++i) {
    if (read(timer, &expirations, sizeof(expirations)) != sizeof(expirations)) return 1;
    say("expired", monotonic_s());
  }
  usleep(600000);  // two more expirations meanwhile (at 1.25 and 1.5 s)
  if (read(timer, &expirations, sizeof(expirations)) != sizeof(expirations)) return 1;
  say("count", static_cast<double>(expirations));
  const int epoll = epoll_create1(0);
  epoll_event event{};
  event.events = EPOLLIN;
  epoll_ctl(epoll, EPOLL_CTL_ADD, timer, &event);
  epoll_event got[1];
  epoll_wait(epoll, got, 1, -1);
  say("epoll_expired", monotonic_s());
  itimerspec left{};
  timerfd_gettime(timer, &left);
  say("left", static_cast<double>(left.it_value.tv_sec) +
                  static_cast<double>(left.it_value.tv_nsec) * 1e-9);
  close(timer);
  return 0;
}

// Timed condition variable and semaphore waits, on each clock they can use.
int cond_waits() {
  std::mutex mutex;
  std::condition_variable condition;
  std::unique_lock<std::mutex> lock(mutex);
  condition.wait_for(lock, std::chrono::milliseconds(300));  // steady_clock: clockwait
  say("wait_for", monotonic_s());
  condition.wait_until(lock, std::chrono::system_clock::now() + std::chrono::milliseconds(200));
  say("wait_until_system", monotonic_s());
  lock.unlock();
  pthread_condattr_t attributes;
  pthread_condattr_init(&attributes);
  pthread_condattr_setclock(&attributes, CLOCK_MONOTONIC);
  pthread_cond_t monotonic_condition;
  pthread_cond_init(&monotonic_condition, &attributes);
  pthread_mutex_t plain_mutex = PTHREAD_MUTEX_INITIALIZER;
  timespec deadline{};
  clock_gettime(CLOCK_MONOTONIC, &deadline);
  deadline.tv_sec += 1;
  pthread_mutex_lock(&plain_mutex);
  const int timed_out = pthread_cond_timedwait(&monotonic_condition, &plain_mutex, &deadline);
  pthread_mutex_unlock(&plain_mutex);
  say("timedwait_monotonic", timed_out == ETIMEDOUT ? monotonic_s() : -1.0);
  sem_t semaphore;
  sem_init(&semaphore, 0, 0);
  clock_gettime(CLOCK_REALTIME, &deadline);
  deadline.tv_nsec += 250000000;
  if (deadline.tv_nsec >= 1000000000) {
    deadline.tv_nsec -= 1000000000;
    deadline.tv_sec += 1;
  }
  const int waited = sem_timedwait(&semaphore, &deadline);
  say("sem_timedwait", waited != 0 && errno == ETIMEDOUT ? monotonic_s() : -1.0);
  // A notify before the deadline ends the wait then.
  std::thread notifier([&] {
    usleep(100000);
    std::lock_guard<std::mutex> guard(mutex);
    condition.notify_all();
  });
  lock.lock();
  const auto status = condition.wait_for(lock, std::chrono::seconds(5));
  say("notified", status == std::cv_status::no_timeout ? monotonic_s() : -1.0);
  lock.unlock();
  notifier.join();
  return 0;
}

// Reads the clock in a loop until 1 s of sim time passed: charged time must
// get it there.
int busy_clock() {
  const double start = monotonic_s();
  long reads = 0;
  while (monotonic_s() - start < 1.0) ++reads;
  say("reads", static_cast<double>(reads));
  say("end", monotonic_s());
  return 0;
}

// Two threads poll the clock until 1 s of sim time, the second starting
// 0.4 ms later: their charged pauses fall on the same instants all the same.
int busy_clock_two() {
  std::thread late([] {
    std::this_thread::sleep_for(std::chrono::microseconds(400));
    const double start = monotonic_s();
    while (monotonic_s() - start < 0.999) {
    }
  });
  const double start = monotonic_s();
  while (monotonic_s() - start < 1.0) {
  }
  late.join();
  say("end", monotonic_s());
  return 0;
}

// A sleep the shim cannot see (a raw syscall): must be reported by name.
int raw_sleep() {
  timespec request{3, 0};
  syscall(SYS_nanosleep, &request, nullptr);
  say("end", monotonic_s());
  return 0;
}

// Starts a program the shim cannot enter (statically linked): the
// controller must say so.
int exec_static(const char* path) {
  execl(path, path, static_cast<char*>(nullptr));
  std::perror("execl");
  return 1;
}

// Timed mutex locks: a thread holds the mutex until 2 s; the timed locks
// before fail at their sim deadlines, the last gets it when it is unlocked.
int timed_mutex() {
  std::timed_mutex mutex;
  std::atomic<bool> held{false};
  std::thread holder([&] {
    std::lock_guard<std::timed_mutex> guard(mutex);
    held.store(true);
    sleep(2);
  });
  while (!held.load()) usleep(1000);
  const double start = monotonic_s();
  say("start", start);
  say("try_lock_for", mutex.try_lock_for(std::chrono::milliseconds(300)) ? -1.0 : monotonic_s());
  say("try_lock_until_system",
      mutex.try_lock_until(std::chrono::system_clock::now() + std::chrono::milliseconds(200))
          ? -1.0
          : monotonic_s());
  pthread_mutex_t plain = PTHREAD_MUTEX_INITIALIZER;
  pthread_mutex_lock(&plain);
  std::thread other([&] {
    timespec deadline{};
    clock_gettime(CLOCK_REALTIME, &deadline);
    deadline.tv_nsec += 250000000;
    if (deadline.tv_nsec >= 1000000000) {
      deadline.tv_nsec -= 1000000000;
      deadline.tv_sec += 1;
    }
    say("timedlock", pthread_mutex_timedlock(&plain, &deadline) == ETIMEDOUT ? monotonic_s() : -1);
  });
  other.join();
  pthread_mutex_unlock(&plain);
  say("locked", mutex.try_lock_for(std::chrono::seconds(10)) ? monotonic_s() : -1.0);
  mutex.unlock();
  holder.join();
  return 0;
}

// Send timeouts (SO_SNDTIMEO) on a full socket, and accept with SO_RCVTIMEO.
int socket_send_accept() {
  int pair[2];
  if (socketpair(AF_UNIX, SOCK_STREAM, 0, pair) != 0) return 1;
  const int size = 4096;
  setsockopt(pair[0], SOL_SOCKET, SO_SNDBUF, &size, sizeof(size));
  char block[1024] = {};
  while (send(pair[0], block, sizeof(block), MSG_DONTWAIT) > 0) {
  }
  const timeval send_timeout{1, 250000};
  setsockopt(pair[0], SOL_SOCKET, SO_SNDTIMEO, &send_timeout, sizeof(send_timeout));
  const ssize_t sent = send(pair[0], block, sizeof(block), 0);
  say("send_timed_out", sent < 0 && errno == EAGAIN ? monotonic_s() : -1.0);
  const ssize_t written = write(pair[0], block, sizeof(block));
  say("write_timed_out", written < 0 && errno == EAGAIN ? monotonic_s() : -1.0);
  timeval seen{};
  socklen_t length = sizeof(seen);
  getsockopt(pair[0], SOL_SOCKET, SO_SNDTIMEO, &seen, &length);
  say("send_timeout", static_cast<double>(seen.tv_sec) + static_cast<double>(seen.tv_usec) * 1e-6);
  const int listener = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (bind(listener, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) return 1;
  listen(listener, 4);
  socklen_t address_length = sizeof(address);
  getsockname(listener, reinterpret_cast<sockaddr*>(&address), &address_length);
  const timeval accept_timeout{0, 750000};
  setsockopt(listener, SOL_SOCKET, SO_RCVTIMEO, &accept_timeout, sizeof(accept_timeout));
  const int none = accept(listener, nullptr, nullptr);
  say("accept_timed_out", none < 0 && errno == EAGAIN ? monotonic_s() : -1.0);
  std::thread connector([address] {
    usleep(250000);
    const int client = socket(AF_INET, SOCK_STREAM, 0);
    if (connect(client, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0)
      std::perror("connect");
    close(client);
  });
  const int accepted = accept(listener, nullptr, nullptr);
  say("accepted", accepted >= 0 ? monotonic_s() : -1.0);
  connector.join();
  return 0;
}

volatile sig_atomic_t queued_value = 0;
void on_queued(int /*signal*/, siginfo_t* info, void* /*context*/) {
  queued_value = info->si_value.sival_int;
}

// A forked child wakes its parent's sleep with a signal (sigqueue, with a
// value) at 1 s and sleeps; the parent sends one back (kill) at 1.5 s,
// which ends the child's sleep then.
int signal_wake() {
  struct sigaction action {};
  action.sa_sigaction = on_queued;
  action.sa_flags = SA_SIGINFO;  // no SA_RESTART: the sleep returns EINTR
  sigemptyset(&action.sa_mask);
  sigaction(SIGUSR1, &action, nullptr);
  const pid_t parent = getpid();
  const pid_t child = fork();
  if (child < 0) return 1;
  if (child == 0) {
    const timespec one{1, 0};
    nanosleep(&one, nullptr);
    sigval value{};
    value.sival_int = 7;
    sigqueue(parent, SIGUSR1, value);
    const timespec long_sleep{20, 0};
    const bool woken = nanosleep(&long_sleep, nullptr) != 0 && errno == EINTR;
    say("child_woken", woken ? monotonic_s() : -1.0);
    _exit(0);
  }
  const timespec ten{10, 0};
  const bool woken = nanosleep(&ten, nullptr) != 0 && errno == EINTR;
  say("parent_woken", woken ? monotonic_s() : -1.0);
  say("value", queued_value);
  const timespec half{0, 500000000};
  nanosleep(&half, nullptr);
  kill(child, SIGUSR1);
  int status = 0;
  waitpid(child, &status, 0);
  say("end", monotonic_s());
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? 0 : 1;
}

std::atomic<int> alarms{0};
void on_alarm(int /*signal*/) {
  alarms.fetch_add(1);
}

// POSIX timers (SIGEV_SIGNAL, SIGEV_THREAD), sigtimedwait, epoll_pwait2,
// alarm and setitimer.
int signal_timers() {
  sigset_t usr1{};
  sigemptyset(&usr1);
  sigaddset(&usr1, SIGUSR1);
  pthread_sigmask(SIG_BLOCK, &usr1, nullptr);
  sigevent event{};
  event.sigev_notify = SIGEV_SIGNAL;
  event.sigev_signo = SIGUSR1;
  event.sigev_value.sival_int = 42;
  timer_t timer{};
  if (timer_create(CLOCK_MONOTONIC, &event, &timer) != 0) return 1;
  itimerspec every{};
  every.it_value.tv_nsec = 500000000;
  every.it_interval.tv_nsec = 250000000;
  timer_settime(timer, 0, &every, nullptr);
  for (int i = 0; i < 3; ++i) {
    siginfo_t info{};
    if (sigwaitinfo(&usr1, &info) != SIGUSR1 || info.si_value.sival_int != 42) return 1;
    say("timer_signal", monotonic_s());
  }
  itimerspec left{};
  timer_gettime(timer, &left);
  say("timer_left", static_cast<double>(left.it_value.tv_nsec) * 1e-9);
  timer_delete(timer);
  // A SIGEV_THREAD timer calls its function in a thread at 1.5 s.
  static std::mutex mutex;
  static std::condition_variable called;
  static double called_at = -1;
  event.sigev_notify = SIGEV_THREAD;
  event.sigev_notify_function = [](sigval) {
    std::lock_guard<std::mutex> guard(mutex);
    called_at = monotonic_s();
    called.notify_all();
  };
  timer_create(CLOCK_REALTIME, &event, &timer);
  itimerspec once{};
  once.it_value.tv_nsec = 500000000;
  timer_settime(timer, 0, &once, nullptr);
  {
    std::unique_lock<std::mutex> lock(mutex);
    called.wait(lock, [] { return called_at >= 0; });
  }
  say("timer_thread", called_at);
  timer_delete(timer);
  const timespec wait_for{0, 400000000};
  siginfo_t info{};
  say("sigtimedwait",
      sigtimedwait(&usr1, &info, &wait_for) < 0 && errno == EAGAIN ? monotonic_s() : -1.0);
  const int epoll = epoll_create1(0);
  epoll_event got[1];
  const timespec epoll_wait_for{0, 100000000};
  say("epoll_pwait2",
      epoll_pwait2(epoll, got, 1, &epoll_wait_for, nullptr) == 0 ? monotonic_s() : -1.0);
  signal(SIGALRM, on_alarm);
  alarm(2);
  say("alarm_left", alarm(2));
  while (alarms.load() == 0) pause();
  say("alarm", monotonic_s());
  itimerval periodic{};
  periodic.it_value.tv_usec = 250000;
  periodic.it_interval.tv_usec = 250000;
  setitimer(ITIMER_REAL, &periodic, nullptr);
  sigset_t none{};
  sigemptyset(&none);
  while (alarms.load() < 3) sigsuspend(&none);
  say("setitimer", monotonic_s());
  itimerval now_left{};
  getitimer(ITIMER_REAL, &now_left);
  say("itimer_left", static_cast<double>(now_left.it_value.tv_usec) * 1e-6);
  return 0;
}

// Waits for another thread with a raw futex (no libc call the shim sees):
// fine with threads that run at once; in deterministic mode the waiter holds
// the run token, the other thread never gets its turn, and the controller
// must name the waiter.
int raw_futex_wait() {
  static std::atomic<std::uint32_t> flag{0};
  std::thread setter([] {
    flag.store(1);
    syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(&flag), FUTEX_WAKE_PRIVATE, 1, nullptr,
            nullptr, 0);
  });
  while (flag.load() == 0) {
    syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(&flag), FUTEX_WAIT_PRIVATE, 0, nullptr,
            nullptr, 0);
  }
  setter.join();
  say("end", monotonic_s());
  return 0;
}

// Threads of two processes write letters straight to stdout (one shared
// file offset), 10 at a time between 1 ms sleeps, with CPU work between
// letters: without the deterministic mode the kernel's scheduler interleaves
// them; with it, each thread writes its 10 in its turn, in a fixed order.
void write_letters(char letter) {
  for (int i = 0; i < 30; ++i) {
    if (write(1, &letter, 1) != 1) std::perror("write");
    volatile unsigned work = 0;
    for (unsigned k = 0; k < 300000; ++k) work = work + k;
    if (i % 10 == 9) usleep(1000);
  }
}

void letters_of_threads(const char* letters) {
  std::vector<std::thread> writers;
  for (const char* letter = letters; *letter != '\0'; ++letter) {
    writers.emplace_back(write_letters, *letter);
  }
  for (auto& writer : writers) writer.join();
}

int interleave() {
  const pid_t child = fork();
  if (child == 0) {
    letters_of_threads("DE");
    _exit(0);
  }
  letters_of_threads("ABC");
  int status = 0;
  waitpid(child, &status, 0);
  if (write(1, "\n", 1) != 1) return 1;
  return 0;
}

// For the benchmark: the CPU time of one clock read (the process CPU clock
// is the kernel's under the shim too).
int clock_cost() {
  constexpr long kCalls = 2000000;
  timespec start{}, end{}, now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &start);
  for (long i = 0; i < kCalls; ++i) clock_gettime(CLOCK_MONOTONIC, &now);
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &end);
  const double spent = static_cast<double>(end.tv_sec - start.tv_sec) * 1e9 +
                       static_cast<double>(end.tv_nsec - start.tv_nsec);
  say("ns_per_clock_read", spent / kCalls);
  return 0;
}

// For the benchmark: the CPU time of an uncontended mutex lock and unlock
// (the shim takes both over in deterministic mode, and passes them on
// otherwise).
int mutex_cost() {
  constexpr long kPairs = 2000000;
  pthread_mutex_t mutex = PTHREAD_MUTEX_INITIALIZER;
  timespec start{}, end{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &start);
  for (long i = 0; i < kPairs; ++i) {
    pthread_mutex_lock(&mutex);
    pthread_mutex_unlock(&mutex);
  }
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &end);
  const double spent = static_cast<double>(end.tv_sec - start.tv_sec) * 1e9 +
                       static_cast<double>(end.tv_nsec - start.tv_nsec);
  say("ns_per_lock_unlock", spent / kPairs);
  return 0;
}

// Four threads pass a baton through one mutex and condition variable: each
// wakes all of them (broadcast), and the baton goes to the thread a counter
// names; the others see it is not theirs and wait again. Nothing is written
// until the end, so in deterministic mode every turn but the last is quiet
// (the shim hands them over itself, shim/handoff.cpp). Prints how many
// wake-ups there were and a hash of who woke in which order (the same on
// every run in deterministic mode). The main thread waits on the same
// condition until they are done.
int baton() {
  constexpr int kThreads = 4;
  constexpr int kPasses = 2000;
  std::mutex mutex;
  std::condition_variable changed;
  int pass = 0;
  int finished = 0;
  std::uint64_t wakes = 0;
  std::uint64_t order_hash = 1469598103934665603ULL;  // FNV-1a
  const auto holder_of = [](int at) { return (at * 7 + at / 3) % kThreads; };
  const auto run = [&](int self) {
    std::unique_lock<std::mutex> lock(mutex);
    while (pass < kPasses) {
      if (holder_of(pass) == self) {
        ++pass;
        changed.notify_all();
      } else {
        changed.wait(lock);
        ++wakes;
        order_hash = (order_hash ^ static_cast<std::uint64_t>(self + 1)) * 1099511628211ULL;
      }
    }
    ++finished;
    changed.notify_all();
  };
  std::vector<std::thread> threads;
  threads.reserve(kThreads);
  for (int i = 0; i < kThreads; ++i) threads.emplace_back(run, i);
  {
    // Waits in the condition, not in a join (a kernel wait that needs the
    // controller's looks), until they are done.
    std::unique_lock<std::mutex> lock(mutex);
    while (finished < kThreads) changed.wait(lock);
  }
  for (auto& thread : threads) thread.join();
  say("wakes", static_cast<double>(wakes));
  std::printf("order %016llx\n", static_cast<unsigned long long>(order_hash));
  return 0;
}

// A thread blocked in a read is woken by another's output of each kind the
// deterministic mode's light looks must notice (light_look.cpp): a write, a
// send, libc's own write of a stdio stream, a close (end of file). Each
// output is followed by a 1 ms sleep: a reader seen late reads the clock
// after sim time moved on. Prints, per kind, the largest lag between an
// output and its reader's wake-up, in sim time.
int fd_wakes() {
  constexpr int kRounds = 25;
  std::array<std::atomic<double>, kRounds> sent_at{};
  const auto reader = [&sent_at](const char* kind, std::vector<int> fds, bool to_end) {
    // The lowest priority: beside a CPU hog, woken, it waits long for a
    // core (the test's point: a look must not miss it on its way).
    const sched_param lowest{0};
    pthread_setschedparam(pthread_self(), SCHED_IDLE, &lowest);
    double worst = 0.0;
    for (int round = 0; round < kRounds; ++round) {
      char byte = 0;
      const int fd = fds[to_end ? round : 0];
      if (read(fd, &byte, 1) != (to_end ? 0 : 1)) std::perror("read");
      worst = std::max(worst, monotonic_s() - sent_at[round].load());
    }
    say((std::string(kind) + "_lag_max").c_str(), worst);
  };
  const auto writer = [&sent_at](const std::function<void(int)>& output) {
    for (int round = 0; round < kRounds; ++round) {
      sent_at[round].store(monotonic_s());
      output(round);
      usleep(1000);
    }
  };
  int piped[2];
  int paired[2];
  int streamed[2];
  if (pipe(piped) != 0 || socketpair(AF_UNIX, SOCK_STREAM, 0, paired) != 0 || pipe(streamed) != 0) {
    return 1;
  }
  std::vector<int> read_ends;
  std::vector<int> write_ends;
  for (int round = 0; round < kRounds; ++round) {
    int ends[2];
    if (pipe(ends) != 0) return 1;
    read_ends.push_back(ends[0]);
    write_ends.push_back(ends[1]);
  }
  FILE* stream = fdopen(streamed[1], "w");
  if (stream == nullptr) return 1;
  const char byte = 'x';
  std::thread woken(reader, "write", std::vector<int>{piped[0]}, false);
  writer([&](int) {
    if (write(piped[1], &byte, 1) != 1) std::perror("write");
  });
  woken.join();
  woken = std::thread(reader, "send", std::vector<int>{paired[1]}, false);
  writer([&](int) {
    if (send(paired[0], &byte, 1, 0) != 1) std::perror("send");
  });
  woken.join();
  woken = std::thread(reader, "stdio", std::vector<int>{streamed[0]}, false);
  writer([&](int) {
    std::fputc(byte, stream);
    std::fflush(stream);
  });
  woken.join();
  woken = std::thread(reader, "close", read_ends, true);
  writer([&](int round) { close(write_ends[round]); });
  woken.join();
  std::fclose(stream);
  return 0;
}

// For the benchmark: 1000 sleeps of 1 ms, each a trip through the controller.
int sleep_cost() {
  for (int i = 0; i < 1000; ++i) usleep(1000);
  say("end", monotonic_s());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::string(argv[1]) == "exec_static") return exec_static(argv[2]);
  const std::map<std::string, std::function<int()>> modes = {
      {"sleeps", sleeps},
      {"fd_timeouts", fd_timeouts},
      {"threads", threads},
      {"forks", forks},
      {"socket_wait", socket_wait},
      {"busy_clock", busy_clock},
      {"busy_clock_two", busy_clock_two},
      {"raw_sleep", raw_sleep},
      {"clock_cost", clock_cost},
      {"sleep_cost", sleep_cost},
      {"receive_timeout", receive_timeout},
      {"timer_fd", timer_fd},
      {"cond_waits", cond_waits},
      {"interleave", interleave},
      {"timed_mutex", timed_mutex},
      {"socket_send_accept", socket_send_accept},
      {"signal_timers", signal_timers},
      {"signal_wake", signal_wake},
      {"raw_futex_wait", raw_futex_wait},
      {"mutex_cost", mutex_cost},
      {"baton", baton},
      {"fd_wakes", fd_wakes}};
  const auto mode = argc == 2 ? modes.find(argv[1]) : modes.end();
  if (mode == modes.end()) {
    std::fprintf(stderr, "usage: timeshim_probe MODE, one of:");
    for (const auto& [name, run] : modes) std::fprintf(stderr, " %s", name.c_str());
    std::fprintf(stderr, " (or: exec_static PATH)\n");
    return 2;
  }
  return mode->second();
}
