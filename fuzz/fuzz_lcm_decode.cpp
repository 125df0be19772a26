// Fuzz target: every LCM type's bounds check and decode (issue 13, item 3).
// The first byte picks the type (lcmtypes/, in name order), the rest is the
// datagram as it would arrive on the bus. What must hold for every input:
//  * the bounds check and lcm-gen's decode agree: what the check accepts,
//    decode reads to the last byte (else the check is too lax: decode would
//    throw or stop short on a message we let through);
//  * nothing the check accepts allocates beyond its size (the fuzz build's
//    64 MB allocation limit and AddressSanitizer catch that);
//  * a decoded message encodes again, to the same size, and that encoding
//    decodes to the same encoding (only a string's terminating byte, which
//    decode skips, may differ from the input).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <utility>

#include "fuzz_support.hpp"
#include "ubersim/bounded_decode.hpp"

namespace {

template <class Msg>
void check_one(const std::uint8_t* data, std::size_t size) {
  const bool accepted = ubersim::EncodedBounds<Msg>::check(data, size);
  Msg message;
  if (!accepted) {
    // decode_bounded must refuse it too, without touching decode.
    if (ubersim::decode_bounded(data, size, message)) std::abort();
    return;
  }
  int consumed = -1;
  try {
    consumed = message.decode(data, 0, static_cast<int>(size));
  } catch (...) {
    std::abort();  // the check let through what decode cannot read
  }
  if (consumed != static_cast<int>(size)) std::abort();
  const std::string first = ubersim::fuzz::encode_or_abort(message);
  if (first.size() != size) std::abort();
  Msg again;
  if (!ubersim::decode_bounded(first.data(), first.size(), again)) std::abort();
  if (ubersim::fuzz::encode_or_abort(again) != first) std::abort();
}

template <class... Msgs, std::size_t... I>
void dispatch(ubersim::LcmTypeList<Msgs...>, std::index_sequence<I...>, std::size_t which,
              const std::uint8_t* data, std::size_t size) {
  ((which == I ? check_one<Msgs>(data, size) : void()), ...);
}

template <class... Msgs>
void dispatch(ubersim::LcmTypeList<Msgs...> types, std::size_t which, const std::uint8_t* data,
              std::size_t size) {
  dispatch(types, std::index_sequence_for<Msgs...>{}, which % sizeof...(Msgs), data, size);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ubersim::fuzz::quiet_logging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  dispatch(ubersim::AllLcmTypes{}, data[0], data + 1, size - 1);
  return 0;
}
