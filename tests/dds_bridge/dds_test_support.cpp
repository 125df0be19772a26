#include "dds_test_support.hpp"

namespace dds_test {

namespace dds = ubersim::dds;

DdsSide::DdsSide(dds_domainid_t domain)
    : domain_(domain), main_(dds::join_domain(domain, dds::DdsNetwork::Loopback)) {}

dds_entity_t DdsSide::new_participant() const {
  return dds::check(dds_create_participant(domain_, nullptr, nullptr), "participant");
}

dds_entity_t make_reader(dds_entity_t participant, dds_entity_t topic, dds::TopicUse use) {
  const dds::Qos qos = dds::peer_qos(use, dds::Role::Reader);
  return dds::check(dds_create_reader(participant, topic, qos.get(), nullptr), "reader");
}

dds_entity_t make_writer(dds_entity_t participant, dds_entity_t topic, dds::TopicUse use) {
  const dds::Qos qos = dds::peer_qos(use, dds::Role::Writer);
  return dds::check(dds_create_writer(participant, topic, qos.get(), nullptr), "writer");
}

namespace {

bool wait_for(const std::function<bool()>& done, double timeout_s) {
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
  while (!done()) {
    if (Clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

}  // namespace

bool wait_for_readers(dds_entity_t writer, double timeout_s, std::uint32_t count) {
  return wait_for(
      [&] {
        dds_publication_matched_status_t status{};
        return dds_get_publication_matched_status(writer, &status) == DDS_RETCODE_OK &&
               status.current_count >= count;
      },
      timeout_s);
}

bool wait_for_writers(dds_entity_t reader, double timeout_s, std::uint32_t count) {
  return wait_for(
      [&] {
        dds_subscription_matched_status_t status{};
        return dds_get_subscription_matched_status(reader, &status) == DDS_RETCODE_OK &&
               status.current_count >= count;
      },
      timeout_s);
}

bool pump_until(ubersim::MessageBus& bus, const std::function<bool()>& done, double timeout_s,
                const std::function<void()>& also) {
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
  while (!done()) {
    if (Clock::now() > deadline) return false;
    bus.wait_and_handle(5);
    if (also) also();
  }
  return true;
}

void pump_for(ubersim::MessageBus& bus, double seconds, const std::function<void()>& also) {
  const auto end = Clock::now() + std::chrono::duration<double>(seconds);
  while (Clock::now() < end) {
    bus.wait_and_handle(5);
    if (also) also();
  }
}

}  // namespace dds_test
