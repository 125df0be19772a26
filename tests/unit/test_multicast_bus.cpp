// Real LCM over UDP multicast (run through run_isolated.sh): two buses in one
// process, as two processes would be, exchange typed messages.
#include <gtest/gtest.h>

#include <ubersim/vision_frame_t.hpp>

#include "ubersim/cli.hpp"
#include "ubersim/message_bus.hpp"

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
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (frames.size() < 100 && std::chrono::steady_clock::now() < deadline) {
    receiver.wait_and_handle(100);
  }
  ASSERT_EQ(frames.size(), 100u);
  for (int64_t i = 0; i < 100; ++i) EXPECT_EQ(frames[static_cast<size_t>(i)], i);
}
