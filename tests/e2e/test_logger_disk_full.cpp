// A log that cannot be written is an error at once: ubersim_logger, alone and
// under tools/launch.sh --log, recording onto a real file system that fills
// up (a 1 MiB tmpfs in a mount namespace of this test's own). The logger must
// stop within a short time of the disk filling, say why in one line, exit
// non-zero, leave a valid LCM log (every event whole) and count in its summary
// exactly the events in the file; the launch script must show that line and
// fail. Needs a mount namespace (root, or unprivileged user namespaces):
// without one it exits 77, which CTest reports as skipped.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sched.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/mount.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <lcm/lcm-cpp.hpp>
#include <optional>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "e2e_support.hpp"
#include "ubersim/common_options.hpp"

namespace {

using e2e::TempDir;
using ubersim::test::ChildProcess;
using Clock = std::chrono::steady_clock;

constexpr std::size_t kDiskBytes = 1 << 20;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A small tmpfs mounted in the test's folder, unmounted when the test ends
// (before the folder is removed). Only this process's mount namespace sees it.
class SmallDisk {
 public:
  explicit SmallDisk(std::string path) : path_(std::move(path)) {
    std::filesystem::create_directories(path_);
    const std::string options = "size=" + std::to_string(kDiskBytes);
    if (::mount("tmpfs", path_.c_str(), "tmpfs", 0, options.c_str()) != 0) {
      throw std::runtime_error("cannot mount a tmpfs on " + path_ + ": " + std::strerror(errno));
    }
  }
  ~SmallDisk() { ::umount2(path_.c_str(), MNT_DETACH); }
  SmallDisk(const SmallDisk&) = delete;
  SmallDisk& operator=(const SmallDisk&) = delete;
  std::string path(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

struct Event {
  std::int64_t number = 0;
  std::string channel;
  std::vector<unsigned char> data;
};

std::uint64_t big_endian(const unsigned char* p, int bytes) {
  std::uint64_t value = 0;
  for (int i = 0; i < bytes; ++i) value = (value << 8) | p[i];
  return value;
}

// Reads an LCM log strictly (lcm::LogFile skips a cut-off last event and
// resynchronises on garbage, so it would pass a broken file): each event
// starts where the previous ended, with the sync word, sane lengths and all
// its bytes, and the file ends exactly after the last one. Empty `problem`
// when the log is valid.
std::vector<Event> read_log_strictly(const std::string& path, std::string& problem) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
  std::vector<Event> events;
  std::size_t at = 0;
  constexpr std::size_t kHeader = 28;
  while (at < bytes.size()) {
    const std::string where = "event " + std::to_string(events.size()) + " at byte " +
                              std::to_string(at) + " of " + std::to_string(bytes.size());
    if (bytes.size() - at < kHeader) return problem = where + ": header cut off", events;
    const unsigned char* p = bytes.data() + at;
    if (big_endian(p, 4) != 0xEDA1DA01) return problem = where + ": no sync word", events;
    Event e;
    e.number = static_cast<std::int64_t>(big_endian(p + 4, 8));
    const auto channel_size = static_cast<std::int32_t>(big_endian(p + 20, 4));
    const auto data_size = static_cast<std::int32_t>(big_endian(p + 24, 4));
    if (channel_size <= 0 || channel_size > 255 || data_size < 0) {
      return problem = where + ": bad lengths", events;
    }
    const std::size_t size = kHeader + channel_size + static_cast<std::size_t>(data_size);
    if (bytes.size() - at < size) return problem = where + ": cut off", events;
    e.channel.assign(p + kHeader, p + kHeader + channel_size);
    e.data.assign(p + kHeader + channel_size, p + size);
    events.push_back(std::move(e));
    at += size;
  }
  return events;
}

// What lcm::LogFile (the reader lcm-logplayer is built on) reads of the file.
std::size_t lcm_logfile_events(const std::string& path) {
  lcm::LogFile log(path, "r");
  std::size_t n = 0;
  while (log.good() && log.readNextEvent() != nullptr) ++n;
  return n;
}

// The number in the logger's summary line, -1 when there is none.
long long summary_count(const std::string& output) {
  static const std::regex summary(R"(recorded (\d+) messages)");
  std::smatch match;
  return std::regex_search(output, match, summary) ? std::stoll(match[1]) : -1;
}

// Checks the log and the logger's output against each other.
void expect_valid_log_counted_in_summary(const std::string& log_path,
                                         const std::string& logger_output) {
  std::string problem;
  const auto events = read_log_strictly(log_path, problem);
  EXPECT_EQ(problem, "") << "the log is not a valid LCM log";
  ASSERT_GT(events.size(), 10u) << "hardly anything was recorded";
  for (std::size_t i = 0; i < events.size(); ++i) {
    ASSERT_EQ(events[i].number, static_cast<std::int64_t>(i)) << "event numbers not consecutive";
  }
  EXPECT_EQ(lcm_logfile_events(log_path), events.size());
  EXPECT_EQ(summary_count(logger_output), static_cast<long long>(events.size()))
      << "the summary must count what reached the file\n"
      << logger_output;
  std::printf("log: %zu events, %llu bytes\n", events.size(),
              static_cast<unsigned long long>(std::filesystem::file_size(log_path)));
}

void expect_error_line(const std::string& output, const std::string& log_path) {
  EXPECT_NE(output.find("cannot write the log '" + log_path + "': No space left on device"),
            std::string::npos)
      << output;
}

TEST(LoggerOnAFullDisk, StopsAtOnceWithAnErrorAndAValidLog) {
  TempDir dir;
  SmallDisk disk(dir.path("disk"));
  const std::string log_path = disk.path("game.lcmlog");
  ChildProcess logger({e2e::bin_dir() + "/ubersim_logger", log_path}, dir.path("logger.out"));
  ASSERT_TRUE(logger.wait_for_output("recording", 10)) << logger.log();

  // 3000-byte messages, one every 2 ms: the disk is full after ~340 of them
  // (never on an event boundary, so a cut-off event is left to clean up).
  ubersim::MessageBus bus(ubersim::default_lcm_url());
  std::vector<unsigned char> payload(3000);
  std::size_t sent_bytes = 0;
  int sent = 0;
  std::optional<Clock::time_point> full;  // when the logger got more than the disk holds
  const auto start = Clock::now();
  while (seconds_since(start) < 30) {
    std::memcpy(payload.data(), &sent, sizeof sent);
    bus.publish_encoded("FILL", payload.data(), payload.size());
    ++sent;
    sent_bytes += payload.size() + 28 + 4;
    if (!full && sent_bytes > kDiskBytes) full = Clock::now();
    if (full && seconds_since(*full) > 5) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    if (!logger.running()) break;
  }
  ASSERT_TRUE(full) << "the disk never filled";
  const double after_full = seconds_since(*full);
  const int status = logger.wait(1);
  std::printf("sent %d messages; the logger ended %.2f s after the disk filled, status %d\n", sent,
              after_full, status);
  EXPECT_LT(after_full, 2.0) << "the logger went on recording onto a full disk";
  EXPECT_EQ(status, 1) << logger.log();
  expect_error_line(logger.log(), log_path);
  expect_valid_log_counted_in_summary(log_path, logger.log());
  // What is in the file is what was sent, in order.
  std::string problem;
  int previous = -1;
  for (const auto& e : read_log_strictly(log_path, problem)) {
    ASSERT_EQ(e.channel, "FILL");
    ASSERT_EQ(e.data.size(), payload.size());
    int number = 0;
    std::memcpy(&number, e.data.data(), sizeof number);
    ASSERT_GT(number, previous);
    previous = number;
  }
}

TEST(LoggerOnAFullDisk, LaunchShowsTheLoggersErrorAndFails) {
  TempDir dir;
  SmallDisk disk(dir.path("disk"));
  const std::string log_path = disk.path("game.lcmlog");
  // As fast as possible with every step's ground truth: the disk is full in
  // about a second; the run itself would last minutes.
  e2e::Launch launch(
      {"--speed", "0", "--duration", "3600", "--truth-every-step", "--log", log_path}, dir);
  const auto start = Clock::now();
  // Polled, not wait(60): on its timeout wait() kills the script with
  // SIGKILL, which would leave the processes it started running.
  auto& script = launch.script();
  while (script.running() && seconds_since(start) < 60) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const bool went_on = script.running();
  const int status = script.stop(10, SIGINT);  // Ctrl-C when it went on; else its status
  const double seconds = seconds_since(start);
  const std::string output = launch.output();
  std::printf("launch.sh ended after %.1f s with status %d\n", seconds, status);
  EXPECT_FALSE(went_on) << "launch.sh went on with the disk full\n" << output;
  EXPECT_NE(status, 0) << output;
  expect_error_line(output, log_path);
  std::ifstream logger_log(dir.path("logs/logger.log"));
  const std::string logger_output((std::istreambuf_iterator<char>(logger_log)),
                                  std::istreambuf_iterator<char>());
  expect_valid_log_counted_in_summary(log_path, logger_output);
}

// The tests' mount namespace: mounts made here are this process's (and its
// children's) only, and vanish with it. 77 (skipped) when it cannot be had.
int enter_private_mount_namespace() {
  if (::unshare(CLONE_NEWNS) != 0) {
    std::printf("SKIPPED: no mount namespace of our own (unshare(CLONE_NEWNS): %s)\n",
                std::strerror(errno));
    return 77;
  }
  if (::mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0) {
    std::printf("SKIPPED: cannot make the mounts private (%s)\n", std::strerror(errno));
    return 77;
  }
  std::string probe = (std::filesystem::temp_directory_path() / "tmpfs-probe.XXXXXX").string();
  if (::mkdtemp(probe.data()) == nullptr) return 1;
  const bool mounted = ::mount("tmpfs", probe.c_str(), "tmpfs", 0, "size=65536") == 0;
  const int mount_errno = errno;
  if (mounted) ::umount2(probe.c_str(), MNT_DETACH);
  ::rmdir(probe.c_str());
  if (!mounted) {
    std::printf("SKIPPED: cannot mount a tmpfs (%s)\n", std::strerror(mount_errno));
    return 77;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (const int status = enter_private_mount_namespace(); status != 0) return status;
  return RUN_ALL_TESTS();
}
