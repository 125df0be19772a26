// ubersim_dds_bridge_benchmark: what the DDS bridge adds and how much it carries.
//
// The real ubersim_dds_bridge process runs with the shipped config; this
// program publishes and listens on both sides at once:
//  1. Latency, SIM_STATE with 22 robots (LCM -> DDS): every message is seen by
//     a direct LCM subscriber and, through the bridge, by a DDS reader; the
//     bridge's added latency is (DDS arrival - direct LCM arrival) of the same
//     message. A direct DDS writer -> reader hop of the same sample, in the
//     same run, is the DDS transport's share.
//  2. Latency, radio packets (DDS -> LCM): the same the other way round.
//  3. Sustained rate: SIM_STATE offered at increasing rates for a second
//     each; what share reaches DDS, and the bridge's CPU.
//  4. CPU per SIM_STATE for the conversion alone, against LCM decoding it.
//
// Run it in a network namespace of its own (DDS and LCM stay on lo):
//   tests/run_isolated.sh bench build-dds/bin/ubersim_dds_bridge_benchmark
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <vector>

#include "child_process.hpp"
#include "dds_test_support.hpp"
#include "sample_messages.hpp"
#include "temp_folder.hpp"
#include "ubersim/bounded_decode.hpp"
#include "ubersim/cli.hpp"
#include "ubersim/dds_bridge/convert.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/process_main.hpp"
#include "ubersim/shutdown.hpp"
#include "ubersim/topics.hpp"

namespace {

namespace dds = ubersim::dds;
using dds_test::Clock;
using ubersim::MessageBus;

const Clock::time_point kStart = Clock::now();
std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - kStart).count();
}

// Arrival times by message index (-1 = not arrived), written by one thread.
struct Arrivals {
  explicit Arrivals(std::size_t n = 0) : at(n, -1) {}
  std::vector<std::int64_t> at;
  std::atomic<std::int64_t> count{0};
  void mark(std::int64_t index) {
    if (index < 0 || static_cast<std::size_t>(index) >= at.size()) return;
    if (at[static_cast<std::size_t>(index)] < 0) at[static_cast<std::size_t>(index)] = now_ns();
    ++count;
  }
};

struct Percentiles {
  double median = 0;
  double p99 = 0;
  std::size_t n = 0;
};

Percentiles percentiles(std::vector<double> v) {
  Percentiles p;
  p.n = v.size();
  if (v.empty()) return p;
  std::sort(v.begin(), v.end());
  p.median = v[v.size() / 2];
  p.p99 = v[std::min(v.size() - 1, static_cast<std::size_t>(0.99 * static_cast<double>(v.size())))];
  return p;
}

// Microseconds from `from` to `to` for every message both saw.
std::vector<double> deltas_us(const std::vector<std::int64_t>& from,
                              const std::vector<std::int64_t>& to) {
  std::vector<double> out;
  for (std::size_t i = 0; i < from.size(); ++i)
    if (from[i] >= 0 && to[i] >= 0) out.push_back(1e-3 * static_cast<double>(to[i] - from[i]));
  return out;
}

void print_row(const char* what, const Percentiles& p) {
  std::printf("  %-52s %9.1f %9.1f   (%zu messages)\n", what, p.median, p.p99, p.n);
}

// A DDS reader whose listener (on Cyclone's thread) marks arrivals at once.
template <class Dds>
class TimedReader {
 public:
  using Index = std::int64_t (*)(const Dds&);
  TimedReader(dds_entity_t participant, const std::string& topic, dds::TopicUse use, Index index)
      : index_(index) {
    const dds_entity_t t = dds_test::make_topic<Dds>(participant, topic);
    dds::Qos qos = dds::peer_qos(use, dds::Role::Reader);
    dds_qset_history(qos.get(), DDS_HISTORY_KEEP_LAST, 64);
    dds_listener_t* listener = dds_create_listener(this);
    dds_lset_data_available(listener, &TimedReader::on_data);
    reader_ = dds::check(dds_create_reader(participant, t, qos.get(), listener), "reader");
    dds_delete_listener(listener);
  }
  ~TimedReader() { dds_delete(reader_); }
  TimedReader(const TimedReader&) = delete;
  TimedReader& operator=(const TimedReader&) = delete;
  void reset(std::size_t n) {
    std::lock_guard<std::mutex> lock(mutex_);
    arrivals_ = std::make_unique<Arrivals>(n);
  }
  // Valid once no more samples come (after the phase).
  Arrivals& arrivals() { return *arrivals_; }
  dds_entity_t get() const { return reader_; }

 private:
  static void on_data(dds_entity_t reader, void* arg) {
    auto* self = static_cast<TimedReader*>(arg);
    std::lock_guard<std::mutex> lock(self->mutex_);
    dds_test::take_each<Dds>(reader, [&](const Dds& sample) {
      if (self->arrivals_) self->arrivals_->mark(self->index_(sample));
    });
  }
  Index index_;
  std::mutex mutex_;
  std::unique_ptr<Arrivals> arrivals_;
  dds_entity_t reader_ = 0;
};

// A thread listening on LCM with its own LCM instance, marking arrivals.
class TimedLcm {
 public:
  explicit TimedLcm(const std::string& url, const ubersim::ChannelNames& channels)
      : bus_(ubersim::with_receive_buffer(url)) {
    ubersim::subscribe(
        bus_, channels, ubersim::topics::kSimState,
        [this](const ubersim::sim_state_t& s) { mark(state_, s.step); }, 100000);
    ubersim::subscribe(
        bus_, channels, ubersim::topics::kRadio.of(ubersim::Team::Yellow),
        [this](const ubersim::radio_packet_t& p) { mark(radio_, p.sequence); }, 100000);
    thread_ = std::thread([this] {
      while (!stop_) bus_.wait_and_handle(20);
    });
  }
  ~TimedLcm() {
    stop_ = true;
    thread_.join();
  }
  void reset(std::size_t states, std::size_t packets) {
    std::lock_guard<std::mutex> lock(mutex_);
    state_ = std::make_unique<Arrivals>(states);
    radio_ = std::make_unique<Arrivals>(packets);
  }
  Arrivals& states() { return *state_; }
  Arrivals& packets() { return *radio_; }

 private:
  void mark(std::unique_ptr<Arrivals>& arrivals, std::int64_t index) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (arrivals) arrivals->mark(index);
  }
  MessageBus bus_;
  std::mutex mutex_;
  std::unique_ptr<Arrivals> state_;
  std::unique_ptr<Arrivals> radio_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

double cpu_seconds_of(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text;
  std::getline(in, text);
  std::istringstream fields(text.substr(text.rfind(')') + 2));
  std::string skip;
  for (int i = 0; i < 11; ++i) fields >> skip;  // state .. cmajflt
  double utime = 0;
  double stime = 0;
  fields >> utime >> stime;
  return (utime + stime) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

// Sleeps until `when` (paces a publisher on the wall clock).
void sleep_until(Clock::time_point when) {
  std::this_thread::sleep_until(when);
}

struct Options {
  int domain = 43;
  int messages = 2000;
  double rate = 240;
  int radio_messages = 600;
  std::vector<double> offered{1000, 2000, 4000, 8000, 12000, 16000, 24000};
};

int run(const Options& options) {
  ubersim::setup_logging("dds_bench", -1);
  const ubersim::ChannelNames channels;
  const std::string url = ubersim::default_lcm_url();
  // The bridge's log: in a folder of the run's own, removed when the run succeeds.
  ubersim::test::TempFolder work("ubersim_dds_bridge_benchmark");
  const std::string log = work.path("bridge.log");
  ubersim::test::ChildProcess bridge(
      {UBERSIM_DDS_BRIDGE_EXE, "--domain", std::to_string(options.domain)}, log);

  dds_test::DdsSide side(options.domain);
  const dds_entity_t writer_participant = side.new_participant();
  const dds_entity_t reader_participant = side.new_participant();
  const auto state_index = [](const dds::DdsSimState& s) { return s.step; };
  const auto radio_index = [](const dds::DdsRadioPacket& p) { return p.sequence_number; };
  TimedReader<dds::DdsSimState> via_bridge(reader_participant, "rt/ubersim/sim_state",
                                           dds::TopicUse::Stream, state_index);
  TimedReader<dds::DdsSimState> direct_dds(reader_participant, "bench/sim_state_direct",
                                           dds::TopicUse::Stream, state_index);
  TimedReader<dds::DdsRadioPacket> radio_direct(reader_participant, "rt/ubersim/radio_yellow",
                                                dds::TopicUse::Command, radio_index);
  const dds_entity_t state_writer = dds_test::make_writer(
      writer_participant,
      dds_test::make_topic<dds::DdsSimState>(writer_participant, "bench/sim_state_direct"),
      dds::TopicUse::Stream);
  const dds_entity_t radio_writer = dds_test::make_writer(
      writer_participant,
      dds_test::make_topic<dds::DdsRadioPacket>(writer_participant, "rt/ubersim/radio_yellow"),
      dds::TopicUse::Command);
  TimedLcm lcm_direct(url, channels);
  MessageBus publisher(url);

  if (!dds_test::wait_for_writers(via_bridge.get(), 20) ||
      !dds_test::wait_for_readers(radio_writer, 20, 2) ||
      !dds_test::wait_for_writers(direct_dds.get(), 20)) {
    std::fprintf(stderr, "DDS discovery did not complete; bridge log %s\n", log.c_str());
    return 1;
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // LCM subscriptions settle

  const auto size_state = dds_test::sim_state(0);
  std::printf("ubersim_dds_bridge_benchmark: bridge pid %d, DDS domain %d, loopback\n",
              static_cast<int>(bridge.pid()), options.domain);
  std::printf("SIM_STATE: %zu robots, %d bytes LCM-encoded\n\n", size_state.robots.size(),
              size_state.getEncodedSize());

  // 1. LCM -> DDS latency, paced.
  const std::size_t n = static_cast<std::size_t>(options.messages);
  via_bridge.reset(n);
  direct_dds.reset(n);
  lcm_direct.reset(n, 0);
  std::vector<std::int64_t> sent(n, -1);
  std::vector<std::int64_t> sent_dds(n, -1);
  const auto period = std::chrono::duration<double>(1.0 / options.rate);
  auto next = Clock::now();
  for (std::size_t i = 0; i < n; ++i) {
    const ubersim::sim_state_t state = dds_test::sim_state(static_cast<std::int64_t>(i));
    const auto sample = dds::to_dds(state);  // converted before timing the direct DDS hop
    sent[i] = now_ns();
    ubersim::publish(publisher, channels, ubersim::topics::kSimState, state);
    sent_dds[i] = now_ns();
    dds_write(state_writer, &sample.get());
    next += std::chrono::duration_cast<Clock::duration>(period);
    sleep_until(next);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  std::printf("LCM -> DDS latency, %zu SIM_STATEs at %.0f Hz (microseconds)   median       p99\n",
              n, options.rate);
  print_row("LCM publish -> LCM subscriber (direct)",
            percentiles(deltas_us(sent, lcm_direct.states().at)));
  print_row("DDS write -> DDS reader (direct)",
            percentiles(deltas_us(sent_dds, direct_dds.arrivals().at)));
  print_row("LCM publish -> bridge -> DDS reader",
            percentiles(deltas_us(sent, via_bridge.arrivals().at)));
  const Percentiles added_state =
      percentiles(deltas_us(lcm_direct.states().at, via_bridge.arrivals().at));
  print_row("added by the bridge (DDS - direct LCM arrival)", added_state);
  std::printf("  lost on the way through the bridge: %zu of %zu\n\n",
              n - percentiles(deltas_us(sent, via_bridge.arrivals().at)).n, n);

  // 2. DDS -> LCM latency (radio packets), paced.
  const std::size_t m = static_cast<std::size_t>(options.radio_messages);
  radio_direct.reset(m);
  lcm_direct.reset(0, m);
  std::vector<std::int64_t> sent_radio(m, -1);
  next = Clock::now();
  for (std::size_t i = 0; i < m; ++i) {
    const auto sample = dds::to_dds(dds_test::radio_packet(0, static_cast<std::int64_t>(i)));
    sent_radio[i] = now_ns();
    dds_write(radio_writer, &sample.get());
    next += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / 120));
    sleep_until(next);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  std::printf("DDS -> LCM latency, %zu radio packets at 120 Hz (microseconds)  median       p99\n",
              m);
  print_row("DDS write -> DDS reader (direct)",
            percentiles(deltas_us(sent_radio, radio_direct.arrivals().at)));
  print_row("DDS write -> bridge -> LCM subscriber",
            percentiles(deltas_us(sent_radio, lcm_direct.packets().at)));
  print_row("added by the bridge (LCM - direct DDS arrival)",
            percentiles(deltas_us(radio_direct.arrivals().at, lcm_direct.packets().at)));
  std::printf("\n");

  // 3. Sustained rate.
  std::printf("SIM_STATE offered for 1 s at each rate: share that reaches DDS, bridge CPU\n");
  std::size_t published_total = n;
  double sustained = 0;
  for (const double rate : options.offered) {
    const std::size_t count = static_cast<std::size_t>(rate);
    via_bridge.reset(count);
    lcm_direct.reset(count, 0);
    std::vector<ubersim::sim_state_t> states;
    states.reserve(count);
    for (std::size_t i = 0; i < count; ++i)
      states.push_back(dds_test::sim_state(static_cast<std::int64_t>(i)));
    const double cpu_before = cpu_seconds_of(bridge.pid());
    const auto start = Clock::now();
    const auto step = std::chrono::duration<double>(1.0 / rate);
    for (std::size_t i = 0; i < count; ++i) {
      ubersim::publish(publisher, channels, ubersim::topics::kSimState, states[i]);
      const auto when =
          start + std::chrono::duration_cast<Clock::duration>(step * static_cast<double>(i + 1));
      if (Clock::now() < when) sleep_until(when);
    }
    const double took = std::chrono::duration<double>(Clock::now() - start).count();
    published_total += count;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    const double cpu = cpu_seconds_of(bridge.pid()) - cpu_before;
    const auto reached = static_cast<double>(via_bridge.arrivals().count.load());
    const auto direct = static_cast<double>(lcm_direct.states().count.load());
    const double share = reached / static_cast<double>(count);
    std::printf(
        "  offered %6.0f Hz (sent in %.2f s): DDS %6.1f %%, direct LCM %6.1f %%, bridge CPU "
        "%.0f %% of a core\n",
        rate, took, 100 * share, 100 * direct / static_cast<double>(count), 100 * cpu / took);
    if (share >= 0.99) sustained = std::max(sustained, static_cast<double>(count) / took);
  }
  std::printf("  sustained (>= 99 %% delivered): %.0f SIM_STATEs per second\n", sustained);
  std::printf("  SIM_STATEs published in the whole run: %zu\n\n", published_total);

  // 4. Conversion CPU against LCM decoding the same message (baseline).
  const auto state = dds_test::sim_state(7);
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(state.getEncodedSize()));
  state.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  constexpr int kRounds = 20000;
  auto t0 = Clock::now();
  std::size_t sink = 0;
  for (int i = 0; i < kRounds; ++i) {
    ubersim::sim_state_t decoded;
    ubersim::decode_bounded(bytes.data(), bytes.size(), decoded);  // what the bridge pays
    sink += decoded.robots.size();
  }
  const double decode_us = 1e6 * std::chrono::duration<double>(Clock::now() - t0).count() / kRounds;
  t0 = Clock::now();
  for (int i = 0; i < kRounds; ++i) sink += dds::to_dds(state).get().robots._length;
  const double convert_us =
      1e6 * std::chrono::duration<double>(Clock::now() - t0).count() / kRounds;
  std::printf(
      "CPU per SIM_STATE (22 robots): LCM decode %.2f us (baseline), LCM -> DDS conversion "
      "%.2f us = %.2fx the decode (%zu)\n",
      decode_us, convert_us, convert_us / decode_us, sink % 2);

  const int status = bridge.stop(10);
  // The bridge's own count says where losses happened: before it (LCM) or after it (DDS).
  std::istringstream lines(bridge.log());
  std::string line;
  while (std::getline(lines, line)) {
    const auto at = line.find("SIM_STATE lcm_to_dds:");
    if (at != std::string::npos)
      std::printf("bridge's own count, whole run: %s\n", line.c_str() + at);
  }
  std::printf("bridge exit status %d\n", status);
  if (status != 0) {
    std::printf("bridge log %s\n", log.c_str());
    return 1;
  }
  work.succeeded();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_dds_bridge_benchmark", [&] {
    Options options;
    CLI::App app{"DDS bridge benchmark: added latency and sustained rate"};
    app.add_option("--domain", options.domain, "DDS domain id")->capture_default_str();
    app.add_option("--messages", options.messages, "SIM_STATEs for the latency phase")
        ->capture_default_str();
    app.add_option("--rate", options.rate, "Hz, SIM_STATE rate of the latency phase")
        ->capture_default_str();
    app.add_option("--offered", options.offered, "Hz, rates tried for the sustained rate");
    if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;
    return run(options);
  });
}
