// Random bytes in deterministic mode (docs/timeshim.md, "Deterministic mode"):
// getrandom and getentropy give each thread the same bytes on every run, from
// a stream seeded with its place in the group's order. A program that seeds
// its generators from them (CPython's random and uuid4, py_trees' behaviour
// ids, whose sets then iterate alike) runs the same way each time. Outside
// the mode, and without the shim, they are the kernel's.
#include <sys/random.h>
#include <sys/types.h>

#include <cerrno>
#include <cstdint>
#include <cstring>

#include "runtime.hpp"

using ubersim::timeshim::shim::deterministic;
using ubersim::timeshim::shim::next_symbol;
using ubersim::timeshim::shim::own_slot;

namespace {

// Trivial, for initial-exec TLS (as the runtime's own record).
struct Stream {
  std::uint64_t state;
  std::uint32_t order_id;  // the place it was seeded for (a forked child reseeds)
  bool seeded;
};
__attribute__((tls_model("initial-exec"))) thread_local Stream stream{};

// splitmix64: small, and each output a good mix of the state.
std::uint64_t next_word() {
  std::uint64_t z = (stream.state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30U)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27U)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31U);
}

void fill(void* buffer, std::size_t length) {
  const std::uint32_t order = own_slot().order_id.load();
  if (!stream.seeded || stream.order_id != order) {
    stream.state = 0x75626572'73696D00ULL ^ (static_cast<std::uint64_t>(order) << 32U);
    stream.order_id = order;
    stream.seeded = true;
  }
  auto* bytes = static_cast<unsigned char*>(buffer);
  while (length > 0) {
    const std::uint64_t word = next_word();
    const std::size_t n = length < sizeof word ? length : sizeof word;
    std::memcpy(bytes, &word, n);
    bytes += n;
    length -= n;
  }
}

}  // namespace

extern "C" {

__attribute__((visibility("default"))) ssize_t getrandom(void* buffer, std::size_t length,
                                                         unsigned int flags) {
  static const auto next = next_symbol<ssize_t (*)(void*, std::size_t, unsigned int)>("getrandom");
  if (!deterministic()) return next(buffer, length, flags);
  fill(buffer, length);
  return static_cast<ssize_t>(length);
}

__attribute__((visibility("default"))) int getentropy(void* buffer, std::size_t length) {
  static const auto next = next_symbol<int (*)(void*, std::size_t)>("getentropy");
  if (!deterministic()) return next(buffer, length);
  if (length > 256) {  // as glibc
    errno = EIO;
    return -1;
  }
  fill(buffer, length);
  return 0;
}

}  // extern "C"
