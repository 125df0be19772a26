#pragma once
// QoS chosen per use of a topic:
//
//   use        channels                                   reliability  history       durability
//   Geometry   SIM_GEOMETRY, VISION_GEOMETRY              reliable     keep-last 1 transient-local
//   Command    RADIO_*, RADIO_FEEDBACK_*, SIM_COMMANDS,   reliable     keep-last 32  volatile
//              SIM_CONTROL, SIM_CONTROL_ACK
//   Stream     VISION, SIM_STATE                          best-effort  keep-last 1   volatile
//
// Geometry is transient-local so a subscriber that joins late still receives
// the field. Streams are best-effort keep-last 1 on the writer: an old state
// is worth nothing once a newer one exists. Our own stream *readers* keep 8
// so that a burst (one frame per camera sent back to back) is not cut to its
// last sample before the bridge takes it.
// Every reader and writer of the bridge ignores data of its own participant
// (ignore-local), so a sample the bridge writes never comes back to it.
#include <dds/dds.h>

#include <type_traits>

#include "ubersim/topics.hpp"

namespace ubersim::dds {

enum class TopicUse { Geometry, Command, Stream };
// A topic's use follows from the message it carries.
template <class Msg>
constexpr TopicUse topic_use(const Topic<Msg>& /*topic*/) {
  if constexpr (std::is_same_v<Msg, vision_frame_t> || std::is_same_v<Msg, sim_state_t>) {
    return TopicUse::Stream;
  } else if constexpr (std::is_same_v<Msg, vision_geometry_t> ||
                       std::is_same_v<Msg, field_geometry_t>) {
    return TopicUse::Geometry;
  } else {
    return TopicUse::Command;
  }
}
const char* topic_use_name(TopicUse use);

struct QosSettings {
  bool reliable = true;
  bool transient_local = false;
  int writer_depth = 1;
  int reader_depth = 1;
};
QosSettings qos_settings(TopicUse use);

// dds_qos_t, deleted with the object.
class Qos {
 public:
  Qos();
  ~Qos();
  Qos(const Qos&) = delete;
  Qos& operator=(const Qos&) = delete;
  Qos(Qos&& other) noexcept : qos_(other.qos_) { other.qos_ = nullptr; }
  Qos& operator=(Qos&&) = delete;
  const dds_qos_t* get() const { return qos_; }
  dds_qos_t* get() { return qos_; }

 private:
  dds_qos_t* qos_;
};

enum class Role { Writer, Reader };
// The bridge's QoS for one endpoint: the table above plus ignore-local.
Qos endpoint_qos(TopicUse use, Role role);
// The same without ignore-local: what another participant (a test, a user's
// program) uses to match the bridge.
Qos peer_qos(TopicUse use, Role role);

}  // namespace ubersim::dds
