#include "ubersim/dds_bridge/bridge.hpp"

#include <sys/eventfd.h>
#include <unistd.h>

#include <array>
#include <functional>
#include <stdexcept>
#include <ubersim/sim_control_t.hpp>

#include "ubersim/dds_bridge/bridged_topics.hpp"
#include "ubersim/dds_bridge/convert.hpp"
#include "ubersim/dds_bridge/dds_entity.hpp"
#include "ubersim/dds_bridge/echo_filter.hpp"
#include "ubersim/dds_bridge/qos.hpp"
#include "ubersim/dds_bridge/sample_checks.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/sim_control_requests.hpp"
#include "ubersim/topics.hpp"

namespace ubersim::dds {

struct Bridge::Link {
  Route route;
  std::string lcm_channel;
  std::string type_name;  // DDS type name
  TopicUse use = TopicUse::Command;
  DdsEntity topic;
  DdsEntity writer;  // LCM -> DDS
  DdsEntity reader;  // DDS -> LCM
  EchoFilter echo;
  RouteStats to_dds;
  RouteStats to_lcm;
  ThrottledLog warnings;
  std::function<int()> take;  // takes and forwards waiting samples; empty unless DDS -> LCM

  std::string label() const { return std::string(route.channel); }
};

namespace {

// Called on Cyclone's thread: only wakes the bridge's loop.
void on_data_available(dds_entity_t /*reader*/, void* arg) {
  const std::uint64_t one = 1;
  const int fd = *static_cast<const int*>(arg);
  // A full eventfd counter (never in practice) still leaves it readable.
  if (write(fd, &one, sizeof one) < 0) return;
}

// Returns loaned samples to the reader whatever happens while they are in use.
class Loan {
 public:
  static constexpr int kBatch = 32;
  explicit Loan(dds_entity_t reader) : reader_(reader) { samples_.fill(nullptr); }
  ~Loan() {
    if (count_ > 0) (void)dds_return_loan(reader_, samples_.data(), count_);
  }
  Loan(const Loan&) = delete;
  Loan& operator=(const Loan&) = delete;

  int take() {
    count_ = dds_take(reader_, samples_.data(), infos_.data(), kBatch, kBatch);
    return count_;
  }
  const void* sample(int i) const { return samples_[static_cast<std::size_t>(i)]; }
  const dds_sample_info_t& info(int i) const { return infos_[static_cast<std::size_t>(i)]; }

 private:
  dds_entity_t reader_;
  std::array<void*, kBatch> samples_{};
  std::array<dds_sample_info_t, kBatch> infos_{};
  int count_ = 0;
};

void record_findings(Bridge::Link& link, const Admission& admission) {
  for (const Finding& finding : admission.findings) {
    ++link.to_lcm.problems[finding.problem];
    link.warnings.warn(link.label() + ":" + finding.problem,
                       "DDS sample on " + link.route.topic + ": " +
                           (admission.forward ? "removed " : "dropped ") + finding.detail);
  }
}

std::string stats_line(const std::string& what, const RouteStats& s) {
  std::string line = what + ": received " + std::to_string(s.received) + ", forwarded " +
                     std::to_string(s.forwarded) + ", dropped " + std::to_string(s.dropped) +
                     ", entries removed " + std::to_string(s.entries_removed) + ", echoes " +
                     std::to_string(s.echoes) + ", write errors " + std::to_string(s.write_errors);
  if (!s.problems.empty()) {
    line += " (";
    bool first = true;
    for (const auto& [problem, count] : s.problems) {
      line += (first ? "" : ", ") + problem + " " + std::to_string(count);
      first = false;
    }
    line += ")";
  }
  return line;
}

// The check a DDS sample of a topic passes before it goes on LCM
// (sample_checks.hpp): finite values, and for commands the radio's limits.
template <class Msg>
auto admission(const Topic<Msg>& /*topic*/, const radio::CommandLimits& /*limits*/) {
  return [](const Msg& message) { return admit(message); };
}

auto admission(const Topic<radio_packet_t>& topic, const radio::CommandLimits& limits) {
  const Team team = topic.name == topics::kRadio.yellow.name ? Team::Yellow : Team::Blue;
  return [limits, team](radio_packet_t& packet) { return admit_radio(packet, team, limits); };
}

auto admission(const Topic<sim_commands_t>& /*topic*/, const radio::CommandLimits& limits) {
  return [limits](sim_commands_t& commands) { return admit_commands(commands, limits); };
}

}  // namespace

template <class Lcm>
void Bridge::publish_lcm(Link& link, const Lcm& message) {
  // Remembered first: the bridge hears its own publication in a later
  // handle_pending() and must know it then.
  if (carries_lcm_to_dds(link.route.direction)) link.echo.remember(lcm_bytes(message));
  bus_.publish(link.lcm_channel, message);
}

template <class Lcm, class Admit>
void Bridge::add(const Topic<Lcm>& lcm_topic, const Route& route, const ChannelNames& channels,
                 Admit admit) {
  using Dds = typename decltype(to_dds(std::declval<const Lcm&>()))::value_type;
  auto link = std::make_unique<Link>();
  Link& l = *link;
  l.route = route;
  l.lcm_channel = channel_name(channels, lcm_topic);
  l.type_name = DdsType<Dds>::descriptor()->m_typename;
  l.use = topic_use(lcm_topic);
  l.topic = DdsEntity(check(dds_create_topic(participant_, DdsType<Dds>::descriptor(),
                                             route.topic.c_str(), nullptr, nullptr),
                            "cannot create DDS topic " + route.topic));

  if (carries_lcm_to_dds(route.direction)) {
    const Qos qos = endpoint_qos(l.use, Role::Writer);
    l.writer = DdsEntity(check(dds_create_writer(participant_, l.topic.get(), qos.get(), nullptr),
                               "cannot create a DDS writer on " + route.topic));
    bus_.subscribe<Lcm>(l.lcm_channel, std::function<void(const Lcm&)>([&l](const Lcm& message) {
                          ++l.to_dds.received;
                          if (!l.echo.empty() && l.echo.is_echo(lcm_bytes(message))) {
                            ++l.to_dds.echoes;
                            return;
                          }
                          const OwnedSample<Dds> sample = to_dds(message);
                          const dds_return_t rc = dds_write(l.writer.get(), &sample.get());
                          if (rc < 0) {
                            ++l.to_dds.write_errors;
                            l.warnings.warn(
                                l.label() + ":write",
                                "DDS write on " + l.route.topic + " failed: " + dds_strretcode(rc));
                            return;
                          }
                          ++l.to_dds.forwarded;
                        }));
  }

  if (carries_dds_to_lcm(route.direction)) {
    const Qos qos = endpoint_qos(l.use, Role::Reader);
    dds_listener_t* listener = dds_create_listener(&wake_fd_);
    dds_lset_data_available(listener, on_data_available);
    const dds_entity_t reader = dds_create_reader(participant_, l.topic.get(), qos.get(), listener);
    dds_delete_listener(listener);  // the reader keeps a copy
    l.reader = DdsEntity(check(reader, "cannot create a DDS reader on " + route.topic));
    l.take = [this, &l, admit]() {
      int taken = 0;
      for (;;) {
        Loan loan(l.reader.get());
        const int n = loan.take();
        if (n < 0) {
          l.warnings.warn(l.label() + ":take",
                          "DDS take on " + l.route.topic + " failed: " + dds_strretcode(n));
          return taken;
        }
        for (int i = 0; i < n; ++i) {
          // Invalid samples only announce a writer leaving or an instance
          // being disposed: nothing to forward.
          if (!loan.info(i).valid_data) continue;
          ++taken;
          ++l.to_lcm.received;
          Lcm message = from_dds(*static_cast<const Dds*>(loan.sample(i)));
          const Admission admission = admit(message);
          record_findings(l, admission);
          l.to_lcm.entries_removed += admission.entries_removed;
          if (!admission.forward) {
            ++l.to_lcm.dropped;
            continue;
          }
          publish_lcm(l, message);
          ++l.to_lcm.forwarded;
        }
        if (n < Loan::kBatch) return taken;
      }
    };
  }
  links_.push_back(std::move(link));
}

Bridge::Bridge(const BridgeConfig& config, const ChannelNames& channels,
               const radio::CommandLimits& radio_limits, dds_entity_t participant, MessageBus& bus)
    : participant_(participant),
      bus_(bus),
      sim_control_channel_(channel_name(channels, topics::kSimControl)) {
  wake_fd_ = eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  if (wake_fd_ < 0) throw std::runtime_error("cannot create an eventfd");
  for_each_bridged_topic([&](const auto& topic) {
    if (const Route* route = config.find(topic))
      add(topic, *route, channels, admission(topic, radio_limits));
  });
}

Bridge::~Bridge() {
  links_.clear();  // readers first: no listener may touch the eventfd after this
  if (wake_fd_ >= 0) close(wake_fd_);
}

int Bridge::take_dds() {
  std::uint64_t count = 0;
  if (read(wake_fd_, &count, sizeof count) < 0) {
    // EAGAIN: nothing signalled; take anyway, a sample may have raced the signal.
  }
  int taken = 0;
  for (const auto& link : links_)
    if (link->take) taken += link->take();
  return taken;
}

void Bridge::request_sim_geometry() {
  const sim_control_t request = geometry_request("ubersim_dds_bridge", 0);
  for (const auto& link : links_) {
    if (link->route.channel == topics::kSimControl.name) {
      publish_lcm(*link, request);
      return;
    }
  }
  bus_.publish(sim_control_channel_, request);
}

const RouteStats& Bridge::stats(std::string_view channel, Direction direction) const {
  for (const auto& link : links_) {
    if (link->route.channel != channel) continue;
    if (direction == Direction::LcmToDds) return link->to_dds;
    if (direction == Direction::DdsToLcm) return link->to_lcm;
  }
  throw std::invalid_argument(std::string("no ") + direction_name(direction) + " route for " +
                              std::string(channel));
}

std::vector<std::string> Bridge::describe_routes() const {
  std::vector<std::string> lines;
  for (const auto& link : links_) {
    const std::string arrow = link->route.direction == Direction::Both       ? " <-> "
                              : link->route.direction == Direction::LcmToDds ? " -> "
                                                                             : " <- ";
    lines.push_back("LCM " + link->lcm_channel + arrow + "DDS " + link->route.topic + " [" +
                    link->type_name + "; " + topic_use_name(link->use) + "]");
  }
  return lines;
}

std::vector<std::string> Bridge::summary() const {
  std::vector<std::string> lines;
  for (const auto& link : links_) {
    if (carries_lcm_to_dds(link->route.direction))
      lines.push_back(stats_line(link->label() + " lcm_to_dds", link->to_dds));
    if (carries_dds_to_lcm(link->route.direction))
      lines.push_back(stats_line(link->label() + " dds_to_lcm", link->to_lcm));
  }
  return lines;
}

}  // namespace ubersim::dds
