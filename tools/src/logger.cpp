// ubersim_logger: records every channel of one LCM bus into an LCM log file,
// like lcm-logger, but without losing messages in bursts: lcm-logger 1.3.1
// keeps LCM's default of 30 queued messages per subscription, and in sync
// mode physics sends SIM_STATE in bursts of hundreds (docs/sync.md). The log
// is an ordinary LCM log: lcm-logplayer replays it.
//
// A log that cannot be written (a full disk, a lost network file system) is
// an error at once, not at the end: the logger says so in one line (file,
// reason, messages in the file), stops recording with the file cut back to
// its last complete message, and exits with kLogWriteFailed, so that
// tools/launch.sh stops the run instead of playing on unrecorded.
#include <CLI/CLI.hpp>
#include <lcm/lcm-cpp.hpp>
#include <string>

#include "lcm_log_writer.hpp"
#include "ubersim/cli.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/process_main.hpp"
#include "ubersim/shutdown.hpp"

namespace {

// Exit statuses (also in --help and docs/design.md).
constexpr int kLogWriteFailed = 1;  // the log could not be created, written or closed

void report_failure(const ubersim::LcmLogWriter& log, std::int64_t received) {
  spdlog::error(
      "cannot write the log '{}': {}; recording stopped, {} messages reached the file "
      "(of {} received), the file ends with the last complete one",
      log.path(), log.error(), log.events(), received);
}

int run(int argc, char** argv) {
  CLI::App app{"ubersim logger: every channel of an LCM bus into an LCM log file, losslessly"};
  app.footer(
      "Exit status: 0 when stopped by SIGINT/SIGTERM with every received message in the file;\n"
      "1 when the log cannot be created, written (e.g. the disk is full) or closed: the logger\n"
      "stops at the first failed write, and the file holds every message up to it, whole.");
  std::string url = ubersim::default_lcm_url();
  std::string channels = ".*";
  std::string path;
  app.add_option("-l,--lcm-url", url, "the bus to record")->capture_default_str();
  app.add_option("--channels", channels, "regular expression of the channels to record")
      ->capture_default_str();
  app.add_option("file", path, "the log file to write (replaced if it exists)")->required();
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;
  ubersim::setup_logging("logger", 0);

  ubersim::LcmLogWriter log(path);
  ubersim::ShutdownSignal shutdown;
  ubersim::MessageBus bus(ubersim::with_receive_buffer(url));
  std::int64_t received = 0;
  bus.subscribe_raw(channels, [&](const std::string& channel, const void* data, std::size_t size,
                                  std::int64_t time) {
    ++received;
    log.write(channel, data, size, time);  // does nothing once a write failed
  });
  spdlog::info("recording {} on {} into {}", channels, url, path);
  while (!shutdown.requested() && !log.failed()) bus.wait_and_handle(100, &shutdown);
  if (!log.failed()) bus.handle_pending();  // what arrived before the signal
  if (!log.close()) {
    report_failure(log, received);
    spdlog::info("recorded {} messages into {}", log.events(), path);
    return kLogWriteFailed;
  }
  spdlog::info("recorded {} messages into {}", log.events(), path);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_logger", [&] { return run(argc, argv); });
}
