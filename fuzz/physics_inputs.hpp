#pragma once
// The input of fuzz_lcm_physics: one byte that picks the channel and the
// physics server's options, then the datagram as it arrives on that channel.
// Shared by the target and the seed writer, so the seeds mean what the target reads.
#include <cstdint>

namespace ubersim::fuzz {

// Every channel the physics server subscribes to.
enum class PhysicsInput : std::uint8_t {
  SimCommands,
  SimControl,
  TruthDemand,
  SyncHorizon,
  VisionSchedule,
  Referee,
  Count
};

// Bits above the channel: which server options the input runs against.
constexpr std::uint8_t kChannelMask = 0x07;
constexpr std::uint8_t kSyncRefereeBit = 0x08;  // --sync-referee (REFEREE is heard)
constexpr std::uint8_t kSyncBit = 0x10;         // --sync (SIM_SYNC_HORIZON drives it)

}  // namespace ubersim::fuzz
