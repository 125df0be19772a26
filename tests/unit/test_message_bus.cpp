// The typed bus over real LCM (the in-process memq:// provider).
#include <gtest/gtest.h>

#include <csignal>
#include <ubersim/radio_packet_t.hpp>

#include "ubersim/message_bus.hpp"
#include "ubersim/shutdown.hpp"

TEST(MessageBus, DeliversTypedMessagesToCallables) {
  ubersim::MessageBus bus("memq://");
  std::vector<int64_t> sequences;
  bus.subscribe<ubersim::radio_packet_t>(
      "RADIO_BLUE", [&](const ubersim::radio_packet_t& p) { sequences.push_back(p.sequence); });
  for (int64_t i = 0; i < 5; ++i) {
    ubersim::radio_packet_t packet{};
    packet.sequence = i;
    bus.publish("RADIO_BLUE", packet);
  }
  EXPECT_EQ(bus.handle_pending(), 5);
  EXPECT_EQ(sequences, (std::vector<int64_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(bus.malformed_count(), 0u);
}

TEST(MessageBus, MalformedMessagesAreCountedAndDropped) {
  ubersim::MessageBus bus("memq://");
  int delivered = 0;
  bus.subscribe<ubersim::radio_packet_t>("RADIO_BLUE",
                                         [&](const ubersim::radio_packet_t&) { ++delivered; });
  const uint8_t garbage[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
  for (int i = 0; i < 3; ++i) bus.publish_encoded("RADIO_BLUE", garbage, sizeof garbage);
  ubersim::radio_packet_t good{};
  bus.publish("RADIO_BLUE", good);
  bus.handle_pending();
  EXPECT_EQ(delivered, 1);
  EXPECT_EQ(bus.malformed_count(), 3u);
  EXPECT_EQ(bus.bad_input().count("decode:RADIO_BLUE"), 3u);
}

TEST(MessageBus, BadUrlIsAClearError) {
  EXPECT_THROW(ubersim::MessageBus("nosuchprovider://x"), std::runtime_error);
}

TEST(Shutdown, SignalWakesAWaitingLoop) {
  ubersim::ShutdownSignal shutdown;
  ubersim::MessageBus bus("memq://");
  EXPECT_FALSE(shutdown.requested());
  std::raise(SIGTERM);
  EXPECT_TRUE(shutdown.requested());
  EXPECT_EQ(shutdown.signal_number(), SIGTERM);
  // Must return at once rather than after the 10 s timeout.
  const auto start = std::chrono::steady_clock::now();
  bus.wait_and_handle(10000, &shutdown);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}
