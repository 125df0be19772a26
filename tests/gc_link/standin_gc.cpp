#include "standin_gc.hpp"

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <stdexcept>

#include "ubersim/gc_link/ci_framing.hpp"

namespace standin {
namespace {

constexpr std::int64_t kSecond = 1'000'000'000;  // ns
constexpr std::int64_t kHalf = 20'000'000;       // us of a half

Referee::Command referee_command(const Command& c) {
  const bool blue = c.for_team() == BLUE;
  switch (c.type()) {
    case Command::HALT:
      return Referee::HALT;
    case Command::STOP:
      return Referee::STOP;
    case Command::NORMAL_START:
      return Referee::NORMAL_START;
    case Command::FORCE_START:
      return Referee::FORCE_START;
    case Command::DIRECT:
      return blue ? Referee::DIRECT_FREE_BLUE : Referee::DIRECT_FREE_YELLOW;
    case Command::KICKOFF:
      return blue ? Referee::PREPARE_KICKOFF_BLUE : Referee::PREPARE_KICKOFF_YELLOW;
    default:
      return Referee::HALT;
  }
}

}  // namespace

StandInGc::StandInGc() {
  listener_ = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t size = sizeof address;
  if (::bind(listener_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
      ::listen(listener_, 1) != 0 ||
      ::getsockname(listener_, reinterpret_cast<sockaddr*>(&address), &size) != 0) {
    throw std::runtime_error("stand-in GC: cannot listen");
  }
  port_ = ntohs(address.sin_port);
  referee_.set_packet_timestamp(0);  // the GC's wall clock: ubersim does not use it
  referee_.set_command_timestamp(0);
  for (auto* team : {referee_.mutable_yellow(), referee_.mutable_blue()}) {
    team->set_name("");
    team->set_score(0);
    team->set_red_cards(0);
    team->set_yellow_cards(0);
    team->set_timeouts(4);
    team->set_timeout_time(300'000'000);
    team->set_goalkeeper(0);
  }
  referee_.set_stage(Referee::NORMAL_FIRST_HALF_PRE);
  referee_.set_command(Referee::HALT);
  referee_.set_command_counter(0);
  referee_.set_stage_time_left(kHalf);
  thread_ = std::thread([this] { serve(); });
}

StandInGc::~StandInGc() {
  ::shutdown(listener_, SHUT_RDWR);
  ::close(listener_);
  thread_.join();
}

std::vector<CiInput> StandInGc::inputs() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return inputs_;
}

std::vector<std::string> StandInGc::wire() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return wire_;
}

void StandInGc::serve() {
  const int fd = ::accept(listener_, nullptr, nullptr);
  if (fd < 0) return;
  ubersim::gc_link::FrameReader reader;
  char buffer[4096];
  while (true) {
    const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
    if (n <= 0) break;
    reader.feed(std::string_view(buffer, static_cast<std::size_t>(n)));
    while (auto bytes = reader.next()) handle(*bytes, fd);
  }
  ::close(fd);
}

void StandInGc::handle(const std::string& bytes, int fd) {
  CiInput input;
  input.ParseFromString(bytes);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    inputs_.push_back(input);
    wire_.push_back(bytes);
  }
  for (const Input& in : input.api_inputs()) {
    if (!in.has_change()) continue;  // reset and config: no output, as in the GC
    apply(in.change());
    send(fd);
  }
  if (input.has_timestamp()) {
    const auto next = tick(input.timestamp());
    send(fd);
    if (next) {  // queued by the tick, applied after its answer, as the GC's engine does
      set_command(*next);
      if (*next == Referee::NORMAL_START && referee_.stage() == Referee::NORMAL_FIRST_HALF_PRE) {
        referee_.set_stage(Referee::NORMAL_FIRST_HALF);
      }
      send(fd);
    }
  }
}

void StandInGc::set_command(Referee::Command command) {
  referee_.set_command(command);
  referee_.set_command_counter(referee_.command_counter() + 1);
  command_since_ = last_time_;
}

void StandInGc::apply(const Change& change) {
  if (change.has_set_status_message_change()) {
    referee_.set_status_message(change.set_status_message_change().status_message());
  } else if (change.has_new_command_change()) {
    set_command(referee_command(change.new_command_change().command()));
  } else if (change.has_change_stage_change()) {
    referee_.set_stage(change.change_stage_change().new_stage());
    referee_.set_stage_time_left(kHalf);
    set_command(Referee::HALT);
  } else if (change.has_update_config_change()) {
    first_kickoff_ = change.update_config_change().first_kickoff_team();
  } else if (change.has_add_game_event_change()) {
    const GameEvent& event = change.add_game_event_change().game_event();
    *referee_.add_game_events() = event;
    if (event.type() == GameEvent::POSSIBLE_GOAL) {
      auto* team = event.possible_goal().by_team() == BLUE ? referee_.mutable_blue()
                                                           : referee_.mutable_yellow();
      team->set_score(team->score() + 1);
      set_command(Referee::HALT);
    }
  }
}

std::optional<Referee::Command> StandInGc::tick(std::int64_t timestamp) {
  const std::int64_t delta = last_time_ < 0 ? 0 : timestamp - last_time_;
  last_time_ = timestamp;
  const auto command = referee_.command();
  if (command == Referee::NORMAL_START || command == Referee::FORCE_START) {
    referee_.set_stage_time_left(referee_.stage_time_left() - delta / 1000);
  }
  // Its auto-continue: STOP held 1 s, then the kick-off; 1 s later NORMAL_START.
  if (timestamp - command_since_ < kSecond) return std::nullopt;
  if (command == Referee::STOP) {
    return first_kickoff_ == BLUE ? Referee::PREPARE_KICKOFF_BLUE : Referee::PREPARE_KICKOFF_YELLOW;
  }
  if (command == Referee::PREPARE_KICKOFF_YELLOW || command == Referee::PREPARE_KICKOFF_BLUE) {
    return Referee::NORMAL_START;
  }
  return std::nullopt;
}

void StandInGc::send(int fd) {
  CiOutput output;
  *output.mutable_referee_msg() = referee_;
  const std::string bytes = ubersim::gc_link::frame(output);
  (void)::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL);
}

}  // namespace standin
