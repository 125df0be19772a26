#pragma once
// RAII for Cyclone DDS C handles: an entity (participant, topic, reader,
// writer, ...) is deleted with its owner object, and every failing call
// becomes a DdsError naming what was being done.
#include <dds/dds.h>

#include <stdexcept>
#include <string>

namespace ubersim::dds {

class DdsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Returns `result` when it is not an error code, else throws DdsError("what: reason").
dds_return_t check(dds_return_t result, const std::string& what);

class DdsEntity {
 public:
  DdsEntity() = default;
  explicit DdsEntity(dds_entity_t handle) : handle_(handle) {}
  ~DdsEntity() { reset(); }
  DdsEntity(const DdsEntity&) = delete;
  DdsEntity& operator=(const DdsEntity&) = delete;
  DdsEntity(DdsEntity&& other) noexcept : handle_(other.handle_) { other.handle_ = 0; }
  DdsEntity& operator=(DdsEntity&& other) noexcept;

  dds_entity_t get() const { return handle_; }
  void reset();  // deletes the entity (and, for a participant, everything in it)

 private:
  dds_entity_t handle_ = 0;
};

// Where DDS traffic may go. Loopback keeps it on this host (Cyclone on `lo`,
// unicast discovery), as LCM's ttl=0 does: the default. Network leaves
// Cyclone's own choice (its default interface, or CYCLONEDDS_URI).
enum class DdsNetwork { Loopback, Network };

// A participant (and, for Loopback, the domain configured for it). When the
// environment sets CYCLONEDDS_URI the user has configured Cyclone: Loopback
// then does not override it.
struct DdsParticipant {
  DdsEntity domain;       // 0 unless the bridge configured the domain itself
  DdsEntity participant;  // declared last: deleted first
  dds_entity_t get() const { return participant.get(); }
};
// Throws DdsError (e.g. for a domain id out of range, or a domain this
// process already joined with another configuration).
DdsParticipant join_domain(dds_domainid_t domain, DdsNetwork network);
// While it lives, Cyclone's own log messages (warnings, errors) go through
// spdlog instead of straight to stderr.
class CycloneLogToSpdlog {
 public:
  CycloneLogToSpdlog();
  ~CycloneLogToSpdlog();
  CycloneLogToSpdlog(const CycloneLogToSpdlog&) = delete;
  CycloneLogToSpdlog& operator=(const CycloneLogToSpdlog&) = delete;
};

// True when CYCLONEDDS_URI is set (Cyclone is configured by the user).
bool cyclone_configured_by_environment();

}  // namespace ubersim::dds
