// The sync client piece over real LCM (UDP multicast, run through
// run_isolated.sh): what a team program says on SYNC_CLIENT when it joins,
// every second after, when it leaves and when it is dropped, read by a second
// bus in the same process standing for the radio emulator.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <ubersim/sync_client_t.hpp>
#include <ubersim/team_t.hpp>
#include <vector>

#include "ubersim/common_options.hpp"
#include "ubersim/process_host.hpp"
#include "ubersim/sync_client.hpp"
#include "ubersim/topics.hpp"

namespace {

using ubersim::ProcessHost;
using ubersim::SyncClient;
using ubersim::Team;
using Clock = SyncClient::Clock;
using namespace std::chrono_literals;

std::string bus_url() {
  return ubersim::with_receive_buffer(ubersim::default_lcm_url());
}

// What the radio emulator hears on one SYNC_CLIENT channel.
class Listener {
 public:
  explicit Listener(const std::string& channel) : bus_(bus_url()) {
    bus_.subscribe<ubersim::sync_client_t>(
        channel, [this](const ubersim::sync_client_t& m) { heard.push_back(m); });
  }
  // Reads until `count` messages arrived (at most 5 s: then the test fails on the count).
  void read_until(std::size_t count) {
    const auto deadline = Clock::now() + 5s;
    while (heard.size() < count && Clock::now() < deadline) bus_.wait_and_handle(50);
  }
  // Reads what is still on its way, so a message that should not have gone out is seen.
  void read_pending() {
    while (bus_.wait_and_handle(50) > 0) {
    }
  }
  // Each message as "hello" or "goodbye".
  std::vector<std::string> said() const {
    std::vector<std::string> out;
    for (const auto& m : heard) out.push_back(m.leaving ? "goodbye" : "hello");
    return out;
  }
  std::vector<ubersim::sync_client_t> heard;

 private:
  ubersim::MessageBus bus_;
};

std::vector<std::uint8_t> encoded(const ubersim::sync_client_t& message) {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(message.getEncodedSize()));
  message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

TEST(SyncClient, JoinsAtOnceSaysItAgainEverySecondAndSaysGoodbyeOnce) {
  const ubersim::ChannelNames channels;
  Listener radio(ubersim::channel_name(channels, ubersim::topics::kSyncClient));
  ubersim::MessageBus bus(bus_url());
  SyncClient client(bus, channels, Team::Blue, "demo_blue");
  const Clock::time_point t0 = Clock::now();
  client.tick(t0);  // not joined yet: nothing
  client.join(t0);
  client.tick(t0 + 999ms);  // not a second yet
  client.tick(t0 + 1s);
  client.tick(t0 + 1500ms);  // a second from the last one, not from the grid
  client.tick(t0 + 2100ms);
  client.leave();
  client.tick(t0 + 5s);  // gone: silent
  client.leave();        // a second goodbye is not said
  radio.read_until(4);
  radio.read_pending();
  EXPECT_EQ(radio.said(), (std::vector<std::string>{"hello", "hello", "hello", "goodbye"}));
  EXPECT_FALSE(client.joined());
  // The bytes the demo team and the SSL bridge built by hand before.
  ubersim::sync_client_t by_hand{};
  by_hand.team = ubersim::team_t::BLUE;
  by_hand.name = "demo_blue";
  ASSERT_FALSE(radio.heard.empty());
  EXPECT_EQ(encoded(radio.heard.front()), encoded(by_hand));
  by_hand.leaving = true;
  EXPECT_EQ(encoded(radio.heard.back()), encoded(by_hand));
}

TEST(SyncClient, ADroppedClientFallsSilentWithoutAGoodbyeUntilItJoinsAgain) {
  const ubersim::ChannelNames channels;
  Listener radio(ubersim::channel_name(channels, ubersim::topics::kSyncClient));
  ubersim::MessageBus bus(bus_url());
  SyncClient client(bus, channels, Team::Yellow, "ssl_bridge_yellow");
  const Clock::time_point t0 = Clock::now();
  client.join(t0);
  client.drop();
  client.tick(t0 + 3s);
  client.leave();
  client.join(t0 + 4s);  // its next answer registers it again
  radio.read_until(2);
  radio.read_pending();
  EXPECT_EQ(radio.said(), (std::vector<std::string>{"hello", "hello"}));
  ASSERT_EQ(radio.heard.size(), 2u);
  EXPECT_EQ(radio.heard[0].team, std::int8_t{ubersim::team_t::YELLOW});
  EXPECT_EQ(radio.heard[1].name, "ssl_bridge_yellow");
}

TEST(SyncClient, SpeaksOnTheChannelTheCommandLineNames) {
  const ubersim::ChannelNames channels("SIM2_", {});
  Listener other_set(ubersim::channel_name(ubersim::ChannelNames(), ubersim::topics::kSyncClient));
  Listener radio("SIM2_SYNC_CLIENT");
  ubersim::MessageBus bus(bus_url());
  SyncClient client(bus, channels, Team::Yellow, "demo_yellow");
  client.join(Clock::now());
  radio.read_until(1);
  other_set.read_pending();
  EXPECT_EQ(radio.said(), std::vector<std::string>{"hello"});
  EXPECT_TRUE(other_set.heard.empty());
}

// Wired to a host as the demo team does: hello before the loop, again after
// the wakeups a second apart, goodbye when the run stops.
TEST(SyncClient, OnAHostItRepeatsAfterWakeupsAndLeavesAtStop) {
  const ubersim::ChannelNames channels;
  Listener radio(ubersim::channel_name(channels, ubersim::topics::kSyncClient));
  ProcessHost host(bus_url(), channels, "demo_yellow");
  SyncClient client(host.bus(), channels, Team::Yellow, "demo_yellow");
  client.join(host.now());
  host.after_wake([&](ProcessHost::Clock::time_point now) { client.tick(now); });
  host.at_stop([&] { client.leave(); });
  // The stop's turn runs the hooks first, at a time past the first repeat.
  host.every(1200ms, [&](ProcessHost::Clock::time_point) { host.stop(0); });
  EXPECT_EQ(host.run(100ms), 0);
  radio.read_until(3);
  radio.read_pending();
  const auto said = radio.said();
  ASSERT_GE(said.size(), 3u);
  EXPECT_EQ(said.front(), "hello");
  EXPECT_EQ(said[1], "hello");
  EXPECT_EQ(said.back(), "goodbye");
  EXPECT_EQ(std::count(said.begin(), said.end(), "goodbye"), 1);
}

}  // namespace
