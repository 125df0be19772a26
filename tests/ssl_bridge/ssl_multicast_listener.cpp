// A team's SSL listener as most SSL software writes it: binds a multicast
// group's port, joins the group on the interface with the address given
// (0.0.0.0: the one the kernel picks, as most stacks do), and counts what it
// hears for a while. Written against the published protocol only.
// Usage: ssl_multicast_listener GROUP PORT JOIN_ADDRESS SECONDS
// Prints "joined" once it listens, then one line of counts:
//   detections=N geometry=N tracked=N referee=N duplicates=N undecodable=N
//   cameras=N assembled=N complete=N
// (duplicates: a detection of one camera and frame number, a tracked frame
// number, or a referee message heard a second time; cameras: camera ids
// heard; assembled, complete: frames put together by frame number as some
// SSL programs do (the detections of the newest number are collected, a
// higher number finishes the frame, a lower one is dropped; the first frame
// heard is not counted), and of them those with a detection of every camera
// heard).
#include <arpa/inet.h>
#include <messages_robocup_ssl_wrapper.pb.h>
#include <poll.h>
#include <ssl_gc_referee_message.pb.h>
#include <ssl_vision_wrapper_tracked.pb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace {

struct Counts {
  int detections = 0;
  int geometry = 0;
  int tracked = 0;
  int referee = 0;
  int duplicates = 0;
  int undecodable = 0;
  std::set<std::pair<std::uint64_t, std::uint64_t>> seen;  // (kind+camera, frame)
  std::set<std::uint32_t> cameras;
  // Assembly by frame number: the frame being collected and its cameras.
  std::int64_t current = -1;
  bool started = false;  // a frame was finished (and not counted) before this one
  std::set<std::uint32_t> current_cameras;
  std::vector<std::size_t> assembled_sizes;  // cameras of each finished frame
};

void assemble(Counts& counts, const SSL_DetectionFrame& detection) {
  counts.cameras.insert(detection.camera_id());
  const auto number = static_cast<std::int64_t>(detection.frame_number());
  if (number < counts.current) return;
  if (number > counts.current) {
    // The first frame is not counted: it may have begun before the join.
    if (counts.current >= 0 && counts.started) {
      counts.assembled_sizes.push_back(counts.current_cameras.size());
    }
    counts.started = counts.current >= 0;
    counts.current = number;
    counts.current_cameras.clear();
  }
  counts.current_cameras.insert(detection.camera_id());
}

void note(Counts& counts, std::uint64_t kind, std::uint64_t number) {
  if (!counts.seen.insert({kind, number}).second) ++counts.duplicates;
}

// Each protocol is told from the others by what it holds: a Referee carries
// a stage and a command, a tracked packet a tracked frame, a vision packet a
// detection or geometry.
void count(Counts& counts, const std::string& bytes) {
  Referee referee;
  // Parsed partially and checked, so that protobuf does not log every other
  // protocol's packet as a Referee missing its required fields.
  if (referee.ParsePartialFromString(bytes) && referee.IsInitialized()) {
    ++counts.referee;
    note(counts, 1, referee.packet_timestamp());
    return;
  }
  TrackerWrapperPacket tracked;
  if (tracked.ParsePartialFromString(bytes) && tracked.IsInitialized() &&
      tracked.has_tracked_frame()) {
    ++counts.tracked;
    note(counts, 2, tracked.tracked_frame().frame_number());
    return;
  }
  SSL_WrapperPacket vision;
  if (vision.ParsePartialFromString(bytes) && vision.IsInitialized() &&
      (vision.has_detection() || vision.has_geometry())) {
    if (vision.has_detection()) {
      ++counts.detections;
      note(counts, 100 + vision.detection().camera_id(), vision.detection().frame_number());
      assemble(counts, vision.detection());
    }
    if (vision.has_geometry()) ++counts.geometry;
    return;
  }
  ++counts.undecodable;
}

int open_listener(const std::string& group, int port, const std::string& join) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) return -1;
  const int one = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  ::inet_pton(AF_INET, group.c_str(), &address.sin_addr);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) return -1;
  ip_mreq membership{};
  membership.imr_multiaddr = address.sin_addr;
  ::inet_pton(AF_INET, join.c_str(), &membership.imr_interface);
  if (::setsockopt(fd, IPPROTO_IP, IP_ADD_MEMBERSHIP, &membership, sizeof membership) != 0) {
    return -1;
  }
  return fd;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: ssl_multicast_listener GROUP PORT JOIN_ADDRESS SECONDS\n");
    return 2;
  }
  const int fd = open_listener(argv[1], std::atoi(argv[2]), argv[3]);
  if (fd < 0) {
    std::perror("listen");
    return 1;
  }
  std::printf("joined %s:%s on %s\n", argv[1], argv[2], argv[3]);
  std::fflush(stdout);
  const auto end =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(std::atof(argv[4]));
  Counts counts;
  std::string buffer(65536, '\0');
  while (std::chrono::steady_clock::now() < end) {
    pollfd wait{fd, POLLIN, 0};
    if (::poll(&wait, 1, 20) <= 0) continue;
    const ssize_t size = ::recv(fd, buffer.data(), buffer.size(), 0);
    if (size > 0) count(counts, buffer.substr(0, static_cast<std::size_t>(size)));
  }
  ::close(fd);
  std::size_t complete = 0;
  for (const std::size_t size : counts.assembled_sizes) complete += size == counts.cameras.size();
  std::printf(
      "detections=%d geometry=%d tracked=%d referee=%d duplicates=%d undecodable=%d cameras=%zu "
      "assembled=%zu complete=%zu\n",
      counts.detections, counts.geometry, counts.tracked, counts.referee, counts.duplicates,
      counts.undecodable, counts.cameras.size(), counts.assembled_sizes.size(), complete);
  return 0;
}
