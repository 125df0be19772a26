#pragma once
// The test's own side of DDS (real Cyclone participants in the test process)
// and of LCM, for the DDS bridge's process tests and benchmark.
#include <dds/dds.h>

#include <array>
#include <chrono>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "ubersim/dds_bridge/dds_entity.hpp"
#include "ubersim/dds_bridge/dds_types.hpp"
#include "ubersim/dds_bridge/qos.hpp"
#include "ubersim/message_bus.hpp"

namespace dds_test {

using Clock = std::chrono::steady_clock;

// The domain, configured as the bridge configures it (loopback), and the
// participants the test creates in it. Deleting it deletes them all.
class DdsSide {
 public:
  explicit DdsSide(dds_domainid_t domain);
  dds_domainid_t domain() const { return domain_; }
  dds_entity_t participant() const { return main_.get(); }
  // Another participant (another "program" on the DDS network).
  dds_entity_t new_participant() const;

 private:
  dds_domainid_t domain_;
  ubersim::dds::CycloneLogToSpdlog cyclone_log_;  // Cyclone's notices through spdlog
  ubersim::dds::DdsParticipant main_;
};

template <class Dds>
dds_entity_t make_topic(dds_entity_t participant, const std::string& name) {
  return ubersim::dds::check(dds_create_topic(participant, ubersim::dds::DdsType<Dds>::descriptor(),
                                              name.c_str(), nullptr, nullptr),
                             "topic " + name);
}
// A reader / writer with the QoS a user's program would use to match the bridge.
dds_entity_t make_reader(dds_entity_t participant, dds_entity_t topic, ubersim::dds::TopicUse use);
dds_entity_t make_writer(dds_entity_t participant, dds_entity_t topic, ubersim::dds::TopicUse use);

// Waits until the writer / reader has matched at least `count` remote endpoints.
bool wait_for_readers(dds_entity_t writer, double timeout_s, std::uint32_t count = 1);
bool wait_for_writers(dds_entity_t reader, double timeout_s, std::uint32_t count = 1);

// Takes every valid sample waiting and calls `each` on it; returns how many.
template <class Dds>
int take_each(dds_entity_t reader, const std::function<void(const Dds&)>& each) {
  int valid = 0;
  for (;;) {
    std::array<void*, 16> samples{};
    std::array<dds_sample_info_t, 16> infos{};
    const int n = dds_take(reader, samples.data(), infos.data(), samples.size(), samples.size());
    if (n <= 0) return valid;
    for (int i = 0; i < n; ++i) {
      if (!infos[static_cast<std::size_t>(i)].valid_data) continue;
      ++valid;
      each(*static_cast<const Dds*>(samples[static_cast<std::size_t>(i)]));
    }
    dds_return_loan(reader, samples.data(), n);
  }
}

// Handles LCM messages (and whatever `also` does each round) until `done`
// holds or the time is up; returns done().
bool pump_until(ubersim::MessageBus& bus, const std::function<bool()>& done, double timeout_s,
                const std::function<void()>& also = {});
// Handles LCM messages for `seconds`.
void pump_for(ubersim::MessageBus& bus, double seconds, const std::function<void()>& also = {});

}  // namespace dds_test
