#pragma once
// The one way bytes from outside become an LCM message: first the schema's
// bounds (generated from lcmtypes/*.lcm, see gen_encoded_bounds.py), then
// lcm-gen's decode, which may then allocate no more than the bytes could hold.
#include <climits>
#include <cstddef>
#include <exception>

#include "ubersim/encoded_bounds.hpp"

namespace ubersim {

// True when data[0, size) is exactly one well-formed encoded Msg, now in out.
template <class Msg>
bool decode_bounded(const void* data, std::size_t size, Msg& out) {
  if (size > static_cast<std::size_t>(INT_MAX) || !EncodedBounds<Msg>::check(data, size)) {
    return false;
  }
  try {
    return out.decode(data, 0, static_cast<int>(size)) == static_cast<int>(size);
  } catch (const std::exception&) {
    return false;  // not expected once the bounds hold; kept so nothing escapes a handler
  }
}

}  // namespace ubersim
