#include "ubersim/dds_bridge/dds_entity.hpp"

#include <cstdlib>
#include <string_view>

#include "ubersim/spdlog.hpp"

namespace ubersim::dds {

dds_return_t check(dds_return_t result, const std::string& what) {
  if (result < 0) throw DdsError(what + ": " + dds_strretcode(result));
  return result;
}

DdsEntity& DdsEntity::operator=(DdsEntity&& other) noexcept {
  if (this != &other) {
    reset();
    handle_ = other.handle_;
    other.handle_ = 0;
  }
  return *this;
}

void DdsEntity::reset() {
  // A child of an already deleted participant is gone too: the error from
  // deleting it again is expected and harmless.
  if (handle_ > 0) (void)dds_delete(handle_);
  handle_ = 0;
}

namespace {

void log_to_spdlog(void* /*userdata*/, const dds_log_data_t* data) {
  // `message` points past Cyclone's own header (time stamp, thread).
  std::string_view text(data->message, data->size);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.remove_suffix(1);
  if ((data->priority & (DDS_LC_FATAL | DDS_LC_ERROR)) != 0) {
    spdlog::error("cyclone: {}", text);
  } else if ((data->priority & DDS_LC_WARNING) != 0 &&
             text.find("not multicast-capable") == std::string_view::npos) {
    spdlog::warn("cyclone: {}", text);
  } else {
    // Informational, and the expected notice that lo has no multicast
    // (Cyclone then discovers peers by unicast, which is what we want).
    spdlog::debug("cyclone: {}", text);
  }
}

}  // namespace

CycloneLogToSpdlog::CycloneLogToSpdlog() {
  dds_set_log_sink(log_to_spdlog, nullptr);
}

CycloneLogToSpdlog::~CycloneLogToSpdlog() {
  dds_set_log_sink(nullptr, nullptr);
}

bool cyclone_configured_by_environment() {
  const char* uri = std::getenv("CYCLONEDDS_URI");
  return uri != nullptr && *uri != '\0';
}

DdsParticipant join_domain(dds_domainid_t domain, DdsNetwork network) {
  // Loopback only: Cyclone finds lo without multicast and discovers its peers
  // on this host by unicast (participant indices on well-known ports).
  static constexpr const char* kLoopbackConfig =
      "<CycloneDDS><Domain Id=\"any\"><General><Interfaces>"
      "<NetworkInterface name=\"lo\"/>"
      "</Interfaces></General></Domain></CycloneDDS>";
  DdsParticipant out;
  if (network == DdsNetwork::Loopback && !cyclone_configured_by_environment()) {
    out.domain = DdsEntity(
        check(dds_create_domain(domain, kLoopbackConfig),
              "cannot create DDS domain " + std::to_string(domain) + " on the loopback interface"));
  }
  out.participant = DdsEntity(check(dds_create_participant(domain, nullptr, nullptr),
                                    "cannot join DDS domain " + std::to_string(domain)));
  return out;
}

}  // namespace ubersim::dds
