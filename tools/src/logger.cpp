// ubersim_logger: records every channel of one LCM bus into an LCM log file,
// like lcm-logger, but without losing messages in bursts: lcm-logger 1.3.1
// keeps LCM's default of 30 queued messages per subscription, and in sync
// mode physics sends SIM_STATE in bursts of hundreds (docs/sync.md). The log
// is an ordinary LCM log: lcm-logplayer replays it.
#include <CLI/CLI.hpp>
#include <lcm/lcm-cpp.hpp>
#include <string>

#include "ubersim/cli.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/process_main.hpp"
#include "ubersim/shutdown.hpp"

namespace {

int run(int argc, char** argv) {
  CLI::App app{"ubersim logger: every channel of an LCM bus into an LCM log file, losslessly"};
  std::string url = ubersim::default_lcm_url();
  std::string channels = ".*";
  std::string path;
  app.add_option("-l,--lcm-url", url, "the bus to record")->capture_default_str();
  app.add_option("--channels", channels, "regular expression of the channels to record")
      ->capture_default_str();
  app.add_option("file", path, "the log file to write (replaced if it exists)")->required();
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;
  ubersim::setup_logging("logger", 0);

  lcm::LogFile log(path, "w");
  if (!log.good()) throw std::runtime_error("cannot write the log '" + path + "'");
  ubersim::ShutdownSignal shutdown;
  ubersim::MessageBus bus(ubersim::with_receive_buffer(url));
  std::int64_t count = 0;
  lcm::LogEvent event{};
  bus.subscribe_raw(channels, [&](const std::string& channel, const void* data, std::size_t size,
                                  std::int64_t received) {
    event.eventnum = count++;
    event.timestamp = received;
    event.channel = channel;
    event.datalen = static_cast<std::int32_t>(size);
    event.data = const_cast<void*>(data);
    log.writeEvent(&event);
  });
  spdlog::info("recording {} on {} into {}", channels, url, path);
  while (!shutdown.requested()) bus.wait_and_handle(100, &shutdown);
  bus.handle_pending();  // what arrived before the signal
  spdlog::info("recorded {} messages", count);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_logger", [&] { return run(argc, argv); });
}
