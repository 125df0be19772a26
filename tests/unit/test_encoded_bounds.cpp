// The generated bounds (lcmtypes/gen_encoded_bounds.py) refuse every datagram
// whose counts or lengths the bytes cannot hold, before lcm-gen's decode can
// allocate for them; the allocation counter below is what shows it.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <new>
#include <stdexcept>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_commands_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/vision_frame_t.hpp>
#include <vector>

#include "ubersim/bounded_decode.hpp"

namespace {
std::atomic<std::size_t> largest_allocation{0};
}  // namespace

// Every allocation of this test program goes through here, so a test can see
// the largest single request a decode made. (GCC pairs the malloc it inlines
// into new with the free in delete and warns; the pair is matched here.)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  std::size_t seen = largest_allocation.load();
  while (size > seen && !largest_allocation.compare_exchange_weak(seen, size)) {
  }
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
#pragma GCC diagnostic pop

namespace {

template <class Msg>
std::vector<std::uint8_t> encode(const Msg& message) {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(message.getEncodedSize()));
  message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

void put_int32(std::vector<std::uint8_t>& bytes, std::size_t at, std::uint32_t value) {
  if (at + 4 > bytes.size()) throw std::out_of_range("put_int32 past the end");
  for (int i = 0; i < 4; ++i) bytes[at + i] = static_cast<std::uint8_t>(value >> (24 - 8 * i));
}

ubersim::sim_commands_t real_commands(int robots) {
  ubersim::sim_commands_t packet{};
  packet.team = 1;
  packet.sequence = 42;
  for (int i = 0; i < robots; ++i) {
    ubersim::robot_command_t command{};
    command.robot_id = i;
    command.vx = 0.5;
    packet.commands.push_back(command);
  }
  packet.num_commands = robots;
  return packet;
}

// Offset of sim_commands_t.num_commands: fingerprint 8, team 1, sequence 8, three doubles.
constexpr std::size_t kNumCommandsAt = 8 + 1 + 8 + 3 * 8;

template <class Msg>
bool refused_without_allocating(const std::vector<std::uint8_t>& bytes) {
  largest_allocation = 0;
  Msg decoded;
  const bool accepted = ubersim::decode_bounded(bytes.data(), bytes.size(), decoded);
  EXPECT_LE(largest_allocation.load(), bytes.size()) << "decode allocated more than the datagram";
  return !accepted;
}

TEST(EncodedBounds, AHugeCountIsRefusedBeforeAnyAllocation) {
  auto bytes = encode(real_commands(6));
  ASSERT_EQ(static_cast<std::size_t>(ubersim::sim_commands_t{}.getEncodedSize()),
            kNumCommandsAt + 4);
  for (std::uint32_t count : {20000000u, 0x7fffffffu, 7u, 0xffffffffu, 0x80000000u}) {
    put_int32(bytes, kNumCommandsAt, count);
    EXPECT_TRUE(refused_without_allocating<ubersim::sim_commands_t>(bytes)) << count;
  }
}

TEST(EncodedBounds, ARealMessageStillDecodes) {
  const auto bytes = encode(real_commands(6));
  ubersim::sim_commands_t decoded;
  ASSERT_TRUE(ubersim::decode_bounded(bytes.data(), bytes.size(), decoded));
  EXPECT_EQ(decoded.commands.size(), 6u);
  EXPECT_EQ(decoded.sequence, 42);
  // One element fewer than claimed: the count no longer fits the bytes left.
  auto fewer = bytes;
  put_int32(fewer, kNumCommandsAt, 7);
  EXPECT_TRUE(refused_without_allocating<ubersim::sim_commands_t>(fewer));
}

TEST(EncodedBounds, EveryTruncationAndExtensionIsRefused) {
  ubersim::sim_state_t state{};
  state.robots.resize(3);
  for (auto& robot : state.robots) {
    robot.robot_type = "omni4";
    robot.wheel_speeds = {1, 2, 3, 4};
    robot.num_wheels = 4;
  }
  state.num_robots = 3;
  auto bytes = encode(state);
  for (std::size_t size = 0; size < bytes.size(); ++size) {
    std::vector<std::uint8_t> truncated(bytes.begin(), bytes.begin() + static_cast<long>(size));
    EXPECT_TRUE(refused_without_allocating<ubersim::sim_state_t>(truncated)) << size;
  }
  bytes.push_back(0);
  EXPECT_TRUE(refused_without_allocating<ubersim::sim_state_t>(bytes));
}

TEST(EncodedBounds, AStringLengthOfZeroOrBeyondTheBytesIsRefused) {
  ubersim::sim_control_t control{};
  control.sender = "referee";
  auto bytes = encode(control);
  // request_id (8) follows the fingerprint, then the sender's int32 length.
  const std::size_t length_at = 8 + 8;
  for (std::uint32_t length : {0u, 0x7fffffffu, 0xffffffffu, 1000u}) {
    put_int32(bytes, length_at, length);
    EXPECT_TRUE(refused_without_allocating<ubersim::sim_control_t>(bytes)) << length;
  }
}

// Found by fuzz_lcm_decode: lcm-gen encodes a string up to its first NUL but
// announces its whole size, so a sender name with a NUL inside, echoed in an
// acknowledgement, went out as a malformed message with stray bytes at its end.
TEST(EncodedBounds, AStringWithANulInsideOrNoneAtItsEndIsRefused) {
  ubersim::sim_control_t control{};
  control.sender = "referee";
  const auto real = encode(control);
  const std::size_t text_at = 8 + 8 + 4;  // fingerprint, request_id, the sender's length
  ASSERT_TRUE(ubersim::decode_bounded(real.data(), real.size(), control));
  auto nul_inside = real;
  nul_inside[text_at + 3] = 0;
  EXPECT_FALSE(ubersim::decode_bounded(nul_inside.data(), nul_inside.size(), control));
  auto no_terminator = real;
  no_terminator[text_at + 7] = 'x';
  EXPECT_FALSE(ubersim::decode_bounded(no_terminator.data(), no_terminator.size(), control));
}

TEST(EncodedBounds, AnotherTypesFingerprintIsRefused) {
  const auto bytes = encode(ubersim::radio_packet_t{});
  EXPECT_TRUE(refused_without_allocating<ubersim::vision_frame_t>(bytes));
}

TEST(EncodedBounds, EveryCountFieldOfAFrameAtMaximumIsRefused) {
  ubersim::vision_frame_t frame{};
  frame.balls.resize(1);
  frame.num_balls = 1;
  const auto bytes = encode(frame);
  // camera_id 4, frame_number 8, two doubles: then num_balls, a ball, and the two team counts.
  const std::size_t num_balls_at = 8 + 4 + 8 + 16;
  const std::size_t yellow_at = num_balls_at + 4 + (4 + 5 * 8);  // a ball: a float, five doubles
  for (std::size_t at : {num_balls_at, yellow_at, yellow_at + 4}) {
    auto hostile = bytes;
    put_int32(hostile, at, 0x7fffffffu);
    EXPECT_TRUE(refused_without_allocating<ubersim::vision_frame_t>(hostile)) << at;
  }
}

}  // namespace
