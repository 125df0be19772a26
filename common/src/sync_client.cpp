#include "ubersim/sync_client.hpp"

#include <ubersim/team_t.hpp>

#include "ubersim/topics.hpp"

namespace ubersim {

SyncClient::SyncClient(MessageBus& bus, const ChannelNames& channels, Team team, std::string name)
    : bus_(bus), channel_(channel_name(channels, topics::kSyncClient)) {
  message_.team = team == Team::Yellow ? team_t::YELLOW : team_t::BLUE;
  message_.name = std::move(name);
}

void SyncClient::join(Clock::time_point now) {
  joined_ = true;
  say(false);
  next_ = now + kRepeat;
}

void SyncClient::tick(Clock::time_point now) {
  if (!joined_ || now < next_) return;
  say(false);
  next_ = now + kRepeat;
}

void SyncClient::leave() {
  if (!joined_) return;
  joined_ = false;
  say(true);
}

void SyncClient::say(bool leaving) {
  message_.leaving = leaving;
  bus_.publish(channel_, message_);
}

}  // namespace ubersim
