// Real LCM over UDP multicast (run through run_isolated.sh): two buses in one
// process, as two processes would be, exchange typed messages.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdint>
#include <ubersim/vision_frame_t.hpp>

#include "ubersim/common_options.hpp"
#include "ubersim/message_bus.hpp"

namespace {
template <class Done>
void handle_until(ubersim::MessageBus& bus, Done done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (!done() && std::chrono::steady_clock::now() < deadline) bus.wait_and_handle(100);
}
}  // namespace

TEST(MulticastBus, TwoInstancesTalkOverUdpm) {
  const std::string url = ubersim::with_receive_buffer(ubersim::default_lcm_url());
  ASSERT_EQ(url.rfind("udpm://", 0), 0u) << url;
  ubersim::MessageBus sender(url);
  ubersim::MessageBus receiver(url);
  std::vector<int64_t> frames;
  receiver.subscribe<ubersim::vision_frame_t>(
      "VISION", [&](const ubersim::vision_frame_t& f) { frames.push_back(f.frame_number); });
  for (int64_t i = 0; i < 100; ++i) {
    ubersim::vision_frame_t frame{};
    frame.frame_number = i;
    sender.publish("VISION", frame);
  }
  handle_until(receiver, [&] { return frames.size() >= 100; });
  ASSERT_EQ(frames.size(), 100u);
  for (int64_t i = 0; i < 100; ++i) EXPECT_EQ(frames[static_cast<size_t>(i)], i);
}

// The kernel drops what no handler of a bus wants: a process pays only for the
// channels it reads. Shown by the sockets' drop counters, and by a recorder's
// bus (a regular expression) that still gets everything.
TEST(MulticastBus, OnlyTheSubscribedChannelsReachTheProcess) {
  const std::string url = ubersim::with_receive_buffer(ubersim::default_lcm_url());
  ubersim::MessageBus sender(url);
  ubersim::MessageBus receiver(url);
  std::vector<int64_t> frames;
  receiver.subscribe<ubersim::vision_frame_t>(
      "VISION", [&](const ubersim::vision_frame_t& f) { frames.push_back(f.frame_number); });
  ASSERT_TRUE(receiver.receives_directly());
  const std::uint64_t receiver_drops_before = receiver.kernel_drops();
  const std::uint64_t sender_drops_before = sender.kernel_drops();
  constexpr int kOthers = 500;
  ubersim::vision_frame_t frame{};
  for (int i = 0; i < kOthers; ++i) sender.publish("VISION_NOT", frame);
  for (int64_t i = 0; i < 100; ++i) {
    frame.frame_number = i;
    sender.publish("VISION", frame);
  }
  handle_until(receiver, [&] { return frames.size() >= 100; });
  ASSERT_EQ(frames.size(), 100u);
  for (int64_t i = 0; i < 100; ++i) EXPECT_EQ(frames[static_cast<size_t>(i)], i);
  // The kernel dropped the 500 others for the receiver, all 600 for the
  // sender (which subscribes to nothing).
  EXPECT_EQ(receiver.kernel_drops() - receiver_drops_before, std::uint64_t{kOthers});
  EXPECT_EQ(sender.kernel_drops() - sender_drops_before, std::uint64_t{kOthers} + 100);

  ubersim::MessageBus recorder(url);
  int recorded_others = 0;
  recorder.subscribe_raw(".*", [&](const std::string& channel, const void*, std::size_t,
                                   std::int64_t) { recorded_others += channel == "VISION_NOT"; });
  // A regular expression goes through LCM's own receive thread, which sees all.
  for (int i = 0; i < kOthers; ++i) sender.publish("VISION_NOT", frame);
  handle_until(recorder, [&] { return recorded_others >= kOthers; });
  EXPECT_EQ(recorded_others, kOthers);
}

// Datagrams sent to the group by hand, not by LCM: what is not a message on a
// subscribed channel never reaches the process; a fragment and an undecodable
// payload are counted and dropped; the valid message after them arrives.
TEST(MulticastBus, HandMadeDatagramsAreDroppedAndCounted) {
  const std::string url = ubersim::with_receive_buffer(ubersim::default_lcm_url());
  const auto address = ubersim::parse_lcm_udpm_url(url).value();
  ubersim::MessageBus receiver(url);
  std::vector<int64_t> frames;
  receiver.subscribe<ubersim::vision_frame_t>(
      "VISION", [&](const ubersim::vision_frame_t& f) { frames.push_back(f.frame_number); });

  const int sender = ::socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(sender, 0);
  const unsigned char ttl = 0;
  ::setsockopt(sender, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl);
  sockaddr_in group{};
  group.sin_family = AF_INET;
  group.sin_port = htons(static_cast<std::uint16_t>(address.port));
  ::inet_pton(AF_INET, address.group.c_str(), &group.sin_addr);
  const auto send = [&](const std::string& datagram) {
    ASSERT_EQ(::sendto(sender, datagram.data(), datagram.size(), 0,
                       reinterpret_cast<const sockaddr*>(&group), sizeof group),
              static_cast<ssize_t>(datagram.size()));
  };
  const std::string header = std::string("LC02") + std::string("\0\0\0\1", 4);
  const std::uint64_t drops_before = receiver.kernel_drops();
  send("not LCM at all");
  send(header + "VISION");                            // no NUL after the name
  send(header + std::string("VISIO\0N", 7));          // another name
  send(std::string("LC03") + std::string(20, '\0'));  // a fragment
  send(header + std::string("VISION\0", 7) + "garbage");
  ubersim::vision_frame_t frame{};
  frame.frame_number = 42;
  std::vector<std::uint8_t> encoded(static_cast<std::size_t>(frame.getEncodedSize()));
  frame.encode(encoded.data(), 0, static_cast<int>(encoded.size()));
  send(header + std::string("VISION\0", 7) + std::string(encoded.begin(), encoded.end()));
  ::close(sender);

  handle_until(receiver, [&] { return !frames.empty(); });
  EXPECT_EQ(frames, std::vector<int64_t>{42});
  EXPECT_EQ(receiver.kernel_drops() - drops_before, 3u);
  EXPECT_EQ(receiver.bad_input().count("lcm:fragment"), 1u);
  EXPECT_EQ(receiver.bad_input().count("decode:VISION"), 1u);
  EXPECT_EQ(receiver.malformed_count(), 2u);
}

// An unhurried subscription (physics' SIM_COMMANDS) never wakes the loop: its
// messages are read when the wait ends for another reason, and never after a
// message sent after them on a channel that does wake the loop (a horizon is
// never handled before the commands it lets physics pass).
TEST(MulticastBus, UnhurriedMessagesWaitForTheNextWakeupAndPrecedeWhatWasSentAfterThem) {
  const std::string url = ubersim::with_receive_buffer(ubersim::default_lcm_url());
  ubersim::MessageBus sender(url);
  ubersim::MessageBus receiver(url);
  std::vector<int64_t> order;  // frame numbers in the order handled
  receiver.subscribe_unhurried<ubersim::vision_frame_t>(
      "UNHURRIED", [&](const ubersim::vision_frame_t& f) { order.push_back(f.frame_number); });
  receiver.subscribe<ubersim::vision_frame_t>(
      "PROMPT", [&](const ubersim::vision_frame_t& f) { order.push_back(f.frame_number); });
  ubersim::vision_frame_t frame{};
  for (int64_t i = 0; i < 3; ++i) {
    frame.frame_number = i;
    sender.publish("UNHURRIED", frame);
  }
  // They wait in the socket: the wait runs to its end (a wakeup would end it
  // within milliseconds), and they are handled then.
  const auto start = std::chrono::steady_clock::now();
  const int handled = receiver.wait_and_handle(300);
  EXPECT_GE(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(250));
  EXPECT_EQ(handled, 3);
  EXPECT_EQ(order, (std::vector<int64_t>{0, 1, 2}));

  // Interleaved: each prompt message comes after every unhurried one sent
  // before it, whatever else is waiting when the loop wakes.
  order.clear();
  constexpr int64_t kMessages = 400;
  for (int64_t i = 0; i < kMessages; ++i) {
    frame.frame_number = i;
    sender.publish(i % 3 == 2 ? "PROMPT" : "UNHURRIED", frame);
  }
  handle_until(receiver, [&] { return order.size() >= static_cast<std::size_t>(kMessages); });
  ASSERT_EQ(order.size(), static_cast<std::size_t>(kMessages));
  std::vector<bool> seen(kMessages, false);
  for (const int64_t number : order) {
    seen[static_cast<std::size_t>(number)] = true;
    if (number % 3 != 2) continue;
    for (int64_t earlier = 0; earlier < number; ++earlier) {
      ASSERT_TRUE(seen[static_cast<std::size_t>(earlier)])
          << "prompt message " << number << " handled before unhurried message " << earlier;
    }
  }
  // handle_pending reads them too, with nothing on the prompt channel.
  order.clear();
  frame.frame_number = 7;
  sender.publish("UNHURRIED", frame);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (order.empty() && std::chrono::steady_clock::now() < deadline) receiver.handle_pending();
  EXPECT_EQ(order, (std::vector<int64_t>{7}));
}

// On a provider without sockets of ubersim's own (memq://, in-process) an
// unhurried subscription is an ordinary one.
TEST(MulticastBus, UnhurriedIsOrdinaryOnMemq) {
  ubersim::MessageBus bus("memq://");
  std::vector<int64_t> frames;
  bus.subscribe_unhurried<ubersim::vision_frame_t>(
      "UNHURRIED", [&](const ubersim::vision_frame_t& f) { frames.push_back(f.frame_number); });
  ubersim::vision_frame_t frame{};
  frame.frame_number = 5;
  bus.publish("UNHURRIED", frame);
  handle_until(bus, [&] { return !frames.empty(); });
  EXPECT_EQ(frames, (std::vector<int64_t>{5}));
  EXPECT_THROW(bus.subscribe_unhurried<ubersim::vision_frame_t>(
                   "UN.*", [](const ubersim::vision_frame_t&) {}),
               std::invalid_argument);
}
