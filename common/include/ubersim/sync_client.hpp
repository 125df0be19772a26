#pragma once
// A team program's membership in sync mode (docs/sync.md): the sync_client_t
// on SYNC_CLIENT that registers it, said again once a second so that a radio
// emulator started later still learns of it, and the goodbye when it leaves.
// The demo team and the SSL bridge (one per team) use it; what the client
// answers on RADIO_<TEAM> is theirs.
//
// Plain calls taking the wall time, so the owner drives it from its host:
//
//   SyncClient sync(host.bus(), host.channels(), Team::Yellow, "demo_yellow");
//   sync.join(host.now());
//   host.after_wake([&](ProcessHost::Clock::time_point now) { sync.tick(now); });
//   host.at_stop([&] { sync.leave(); });
#include <chrono>
#include <string>
#include <ubersim/sync_client_t.hpp>

#include "ubersim/channels.hpp"
#include "ubersim/message_bus.hpp"

namespace ubersim {

class SyncClient {
 public:
  using Clock = std::chrono::steady_clock;
  // How often the registration is said again (wall time).
  static constexpr std::chrono::seconds kRepeat{1};

  // `name` is the client's name in the radio emulator's logs and statistics.
  SyncClient(MessageBus& bus, const ChannelNames& channels, Team team, std::string name);

  // Registers: says so now, and tick() says it again every kRepeat from now.
  void join(Clock::time_point now);
  // Says the registration again when kRepeat has passed since it was last
  // said (call it after every wakeup). Nothing while not joined.
  void tick(Clock::time_point now);
  // Says goodbye (leaving = true) if joined; then silent until join().
  void leave();
  // Falls silent without a goodbye: a client dropped for not answering in
  // time. The radio emulator owes it the same frames and drops it by its own
  // timeout, which marks the run degraded where the user looks (docs/sync.md,
  // "A dropped client"); a goodbye would not.
  void drop() { joined_ = false; }

  // A timed client (a team under the time shim): its radio packets carry their
  // send time, and an empty one is a promise (docs/sync.md, "Timed clients").
  void set_timed(bool timed) { message_.timed = timed; }

  bool joined() const { return joined_; }
  const std::string& name() const { return message_.name; }

 private:
  void say(bool leaving);

  MessageBus& bus_;
  std::string channel_;
  sync_client_t message_{};
  bool joined_ = false;
  Clock::time_point next_{};
};

}  // namespace ubersim
