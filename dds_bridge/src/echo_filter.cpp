#include "ubersim/dds_bridge/echo_filter.hpp"

#include <algorithm>
#include <string_view>

namespace ubersim::dds {
namespace {

std::uint64_t hash_of(const EchoFilter::Bytes& bytes) {
  return std::hash<std::string_view>{}(
      std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace

void EchoFilter::remember(Bytes bytes, Clock::time_point now) {
  forget_older_than(now);
  if (sent_.size() >= capacity_) sent_.pop_front();
  const std::uint64_t hash = hash_of(bytes);
  sent_.push_back({now, hash, std::move(bytes)});
}

bool EchoFilter::is_echo(const Bytes& bytes, Clock::time_point now) {
  forget_older_than(now);
  if (sent_.empty()) return false;
  const std::uint64_t hash = hash_of(bytes);
  return std::any_of(sent_.begin(), sent_.end(),
                     [&](const Sent& s) { return s.hash == hash && s.bytes == bytes; });
}

void EchoFilter::forget_older_than(Clock::time_point now) {
  while (!sent_.empty() && now - sent_.front().time > window_) sent_.pop_front();
}

}  // namespace ubersim::dds
