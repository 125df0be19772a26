#pragma once
// Owning the heap parts of a C DDS sample. Our conversions allocate every
// sequence buffer with dds_alloc and every string with dds_string_dup and mark
// sequences _release, so dds_sample_free(DDS_FREE_CONTENTS) with the topic's
// descriptor returns all of it; OwnedSample does that in its destructor.
#include <cstddef>
#include <cstring>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "ubersim/dds_bridge/dds_types.hpp"

namespace ubersim::dds {

template <class T>
class OwnedSample {
  static_assert(std::is_trivially_copyable_v<T>, "a generated C type");

 public:
  using value_type = T;

  OwnedSample() = default;
  ~OwnedSample() { dds_sample_free(&value_, DdsType<T>::descriptor(), DDS_FREE_CONTENTS); }
  OwnedSample(const OwnedSample&) = delete;
  OwnedSample& operator=(const OwnedSample&) = delete;
  OwnedSample(OwnedSample&& other) noexcept : value_(other.value_) { other.value_ = T{}; }
  OwnedSample& operator=(OwnedSample&& other) noexcept {
    std::swap(value_, other.value_);
    return *this;
  }

  T& get() { return value_; }
  const T& get() const { return value_; }

 private:
  T value_{};  // zeroed: empty sequences, null strings
};

// A string the sample owns (dds_sample_free releases it).
inline char* dds_string(const std::string& text) {
  return dds_string_dup(text.c_str());
}
// A string from a received sample; a null pointer reads as "".
inline std::string from_dds_string(const char* text) {
  return text != nullptr ? text : "";
}

// Fills a generated sequence (_maximum, _length, _buffer, _release) with
// source.size() zeroed elements, each then set by convert(source[i], element).
template <class Sequence, class Source, class Convert>
void fill_sequence(Sequence& sequence, const std::vector<Source>& source, Convert convert) {
  using Element = std::remove_pointer_t<decltype(sequence._buffer)>;
  const std::size_t n = source.size();
  sequence._length = sequence._maximum = static_cast<std::uint32_t>(n);
  sequence._release = true;
  sequence._buffer = nullptr;
  if (n == 0) return;
  sequence._buffer = static_cast<Element*>(dds_alloc(n * sizeof(Element)));
  std::memset(static_cast<void*>(sequence._buffer), 0, n * sizeof(Element));
  for (std::size_t i = 0; i < n; ++i) convert(source[i], sequence._buffer[i]);
}

// A sequence of numbers, element for element.
template <class Sequence, class Number>
void fill_sequence(Sequence& sequence, const std::vector<Number>& source) {
  static_assert(std::is_arithmetic_v<Number>, "a sequence of numbers");
  fill_sequence(sequence, source, [](Number from, auto& to) { to = from; });
}

// The elements of a received sequence, each converted.
template <class Target, class Sequence, class Convert>
std::vector<Target> from_dds_sequence(const Sequence& sequence, Convert convert) {
  std::vector<Target> out;
  if (sequence._buffer == nullptr) return out;
  out.reserve(sequence._length);
  for (std::uint32_t i = 0; i < sequence._length; ++i) out.push_back(convert(sequence._buffer[i]));
  return out;
}

template <class Sequence>
auto from_dds_sequence(const Sequence& sequence) {
  using Number = std::remove_cv_t<std::remove_pointer_t<decltype(sequence._buffer)>>;
  return from_dds_sequence<Number>(sequence, [](Number value) { return value; });
}

// The int32 element count LCM carries next to each array.
template <class T>
std::int32_t count_of(const std::vector<T>& items) {
  return static_cast<std::int32_t>(items.size());
}

}  // namespace ubersim::dds
