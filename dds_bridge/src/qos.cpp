#include "ubersim/dds_bridge/qos.hpp"

#include <stdexcept>

namespace ubersim::dds {

const char* topic_use_name(TopicUse use) {
  switch (use) {
    case TopicUse::Geometry:
      return "reliable, keep-last 1, transient-local";
    case TopicUse::Command:
      return "reliable, keep-last 32, volatile";
    case TopicUse::Stream:
      return "best-effort, keep-last 1, volatile";
  }
  return "?";
}

QosSettings qos_settings(TopicUse use) {
  switch (use) {
    case TopicUse::Geometry:
      return {true, true, 1, 1};
    case TopicUse::Command:
      return {true, false, 32, 32};
    case TopicUse::Stream:
      return {false, false, 1, 8};
  }
  return {};
}

Qos::Qos() : qos_(dds_create_qos()) {
  if (qos_ == nullptr) throw std::bad_alloc();
}

Qos::~Qos() {
  if (qos_ != nullptr) dds_delete_qos(qos_);
}

Qos peer_qos(TopicUse use, Role role) {
  const QosSettings s = qos_settings(use);
  Qos qos;
  dds_qset_reliability(qos.get(),
                       s.reliable ? DDS_RELIABILITY_RELIABLE : DDS_RELIABILITY_BEST_EFFORT,
                       DDS_MSECS(100));
  dds_qset_history(qos.get(), DDS_HISTORY_KEEP_LAST,
                   role == Role::Writer ? s.writer_depth : s.reader_depth);
  dds_qset_durability(qos.get(),
                      s.transient_local ? DDS_DURABILITY_TRANSIENT_LOCAL : DDS_DURABILITY_VOLATILE);
  // Transient-local data is served from the writer's own history: a late
  // joiner receives the last writer_depth samples (the current geometry).
  return qos;
}

Qos endpoint_qos(TopicUse use, Role role) {
  Qos qos = peer_qos(use, role);
  dds_qset_ignorelocal(qos.get(), DDS_IGNORELOCAL_PARTICIPANT);
  return qos;
}

}  // namespace ubersim::dds
