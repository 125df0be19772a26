#pragma once
// One team's command link, in sim time: rate limit with "latest command wins",
// per-packet and per-robot loss, latency with jitter that never reorders.
//
// The link transmits at most one packet per 1 / MAX_PACKET_RATE. A packet that
// arrives while the link is free goes out at once; one that arrives while it is
// busy waits, and a newer arrival replaces it (the stale one is counted as
// superseded). The waiting packet goes out at the exact sim time the link frees
// (poll() is called on every SIM_STATE, and the time it is stamped with is the
// moment the link freed, not the step that noticed it), so a saturated link
// runs at exactly its rate whatever the physics step.
//
// The result is a sim_commands_t with t_apply = transmission time + delay;
// physics holds it until then. Loss happens in the air: a lost packet still
// used its transmission slot.
#include <cstdint>
#include <optional>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_commands_t.hpp>

#include "ubersim/radio/link_random.hpp"
#include "ubersim/radio/radio_profile.hpp"

namespace ubersim::radio {

struct CommandLinkStats {
  std::uint64_t offered = 0;            // packets handed to the link
  std::uint64_t superseded = 0;         // replaced by a newer packet while waiting
  std::uint64_t transmitted = 0;        // went on the air
  std::uint64_t lost_packets = 0;       // lost whole
  std::uint64_t lost_entries = 0;       // robot entries lost from packets that got through
  std::uint64_t forwarded_packets = 0;  // published on SIM_COMMANDS
  std::uint64_t forwarded_entries = 0;
};

class CommandLink {
 public:
  // Times closer than this count as equal (sim times are sums of float steps).
  static constexpr double kTimeEpsilon = 1e-6;  // s

  CommandLink(const RadioProfile& profile, Team team, std::uint64_t seed);

  // A (validated) packet arrives at sim time `now`. Returns what to publish if
  // it went out at once and got through.
  std::optional<sim_commands_t> offer(radio_packet_t packet, double now);
  // Sim time has reached `now`: transmits the waiting packet if the link is free.
  std::optional<sim_commands_t> poll(double now);
  // The world was reset: forget the waiting packet and the link's timing.
  void reset();
  // New delay and loss from the next transmission on (a run-time realism change).
  void set_profile(const RadioProfile& profile);

  // Sync mode (docs/sync.md): the earliest t_apply a packet not yet
  // transmitted can get, when no packet can arrive before `earliest_arrival`
  // (+inf: none will). Exact, because the next delay is drawn ahead.
  double earliest_apply(double earliest_arrival) const;

  bool has_waiting_packet() const { return waiting_.has_value(); }
  double busy_until() const { return busy_until_; }
  const CommandLinkStats& stats() const { return stats_; }

 private:
  struct Waiting {
    radio_packet_t packet;
    double t_received;
  };
  bool free_at(double t) const { return t + kTimeEpsilon >= busy_until_; }
  std::optional<sim_commands_t> transmit(Waiting waiting, double t_transmit);

  RadioProfile profile_;
  Team team_;
  LinkRandom random_;
  std::optional<Waiting> waiting_;
  double busy_until_;
  double last_t_apply_;
  // The next transmission's delay, drawn one packet ahead so that the earliest
  // moment a command can take effect is known before the packet exists.
  double next_delay_;
  CommandLinkStats stats_;
};

}  // namespace ubersim::radio
