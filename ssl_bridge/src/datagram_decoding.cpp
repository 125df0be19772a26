#include "ubersim/ssl_bridge/datagram_decoding.hpp"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/unknown_field_set.h>

#include <string>
#include <vector>

namespace ubersim::ssl {
namespace {

using google::protobuf::FieldDescriptor;
using google::protobuf::Message;
using google::protobuf::Reflection;

// Walks every message inside `message` (bounded: the decode already limited
// depth and size). Counts unknown fields and names the first over-long
// repeated field; false when one was found.
bool check_message(const Message& message, std::size_t& unknown, std::string& too_long) {
  const Reflection* reflection = message.GetReflection();
  unknown += static_cast<std::size_t>(reflection->GetUnknownFields(message).field_count());
  std::vector<const FieldDescriptor*> fields;
  reflection->ListFields(message, &fields);
  for (const FieldDescriptor* field : fields) {
    if (field->is_repeated()) {
      const int count = reflection->FieldSize(message, field);
      if (count > kMaxRepeatedElements) {
        too_long = field->full_name() + " holds " + std::to_string(count) + " elements";
        return false;
      }
      if (field->cpp_type() != FieldDescriptor::CPPTYPE_MESSAGE) continue;
      for (int i = 0; i < count; ++i) {
        if (!check_message(reflection->GetRepeatedMessage(message, field, i), unknown, too_long)) {
          return false;
        }
      }
    } else if (field->cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE) {
      if (!check_message(reflection->GetMessage(message, field), unknown, too_long)) return false;
    }
  }
  return true;
}

bool read_varint(const std::uint8_t*& p, const std::uint8_t* end, std::uint64_t& value) {
  value = 0;
  for (int shift = 0; shift < 64 && p < end; shift += 7) {
    const std::uint8_t byte = *p++;
    value |= static_cast<std::uint64_t>(byte & 0x7f) << shift;
    if ((byte & 0x80) == 0) return true;
  }
  return false;
}

// Walks the wire format of one message of type `type` (null: an unknown
// group or field) in [p, end) before protobuf parses it: every length must fit
// in the bytes left of its enclosing message, at every depth. protobuf 3.21
// checks a nested field's length only after reserving min(length, 50 MB) for
// it, so 454 bytes could reserve 50 MB (found by fuzz_ssl_control).
// `group` is the field number whose end-group tag ends this message (0: none).
bool lengths_fit(const std::uint8_t*& p, const std::uint8_t* end,
                 const google::protobuf::Descriptor* type, int depth, std::uint64_t group) {
  if (depth > kDecodeRecursionLimit) return false;
  while (p < end) {
    std::uint64_t tag = 0;
    if (!read_varint(p, end, tag)) return false;
    const std::uint64_t number = tag >> 3;
    const FieldDescriptor* field = type != nullptr && number <= 0x1fffffff
                                       ? type->FindFieldByNumber(static_cast<int>(number))
                                       : nullptr;
    std::uint64_t value = 0;
    switch (tag & 7) {
      case 0:
        if (!read_varint(p, end, value)) return false;
        break;
      case 1:
        if (end - p < 8) return false;
        p += 8;
        break;
      case 5:
        if (end - p < 4) return false;
        p += 4;
        break;
      case 2: {
        if (!read_varint(p, end, value) || value > static_cast<std::uint64_t>(end - p)) {
          return false;
        }
        const std::uint8_t* inner = p;
        p += value;
        if (field != nullptr && field->type() == FieldDescriptor::TYPE_MESSAGE &&
            !lengths_fit(inner, p, field->message_type(), depth + 1, 0)) {
          return false;
        }
        break;
      }
      case 3: {
        const bool known = field != nullptr && field->type() == FieldDescriptor::TYPE_GROUP;
        if (!lengths_fit(p, end, known ? field->message_type() : nullptr, depth + 1, number)) {
          return false;
        }
        break;
      }
      case 4:
        return group != 0 && number == group;
      default:
        return false;
    }
  }
  return group == 0;
}

}  // namespace

DecodedDatagram decode_datagram(const std::uint8_t* data, std::size_t size, Message& message,
                                Errors& errors, bool missing_required_ok) {
  DecodedDatagram result;
  message.Clear();
  const std::string type = message.GetTypeName();
  if (size > kMaxDatagramBytes) {
    add_error(errors, kErrorTooLarge,
              "datagram of " + std::to_string(size) + " bytes: at most " +
                  std::to_string(kMaxDatagramBytes) + " fit in one UDP datagram");
    return result;
  }
  // ParseFromArray, not a CodedInputStream with a lower recursion limit: only
  // a flat-array parse knows the input ends here, and caps what a string or
  // unknown field's claimed length reserves by it. Over a stream, 115 bytes
  // claiming a 64 MB field reserved 50 MB (found by fuzz_ssl_robot_control).
  const std::uint8_t* walk = data;
  if (!lengths_fit(walk, data + size, message.GetDescriptor(), 0, 0) ||
      !(missing_required_ok ? message.ParsePartialFromArray(data, static_cast<int>(size))
                            : message.ParseFromArray(data, static_cast<int>(size)))) {
    message.Clear();
    add_error(errors, kErrorMalformed,
              "datagram does not decode as " + type + " (" + std::to_string(size) +
                  " bytes: cut short, a required field missing, or nested deeper than " +
                  std::to_string(kDecodeRecursionLimit) + ")");
    return result;
  }
  std::string too_long;
  if (!check_message(message, result.unknown_fields, too_long)) {
    message.Clear();
    add_error(errors, kErrorTooLarge,
              type + ": " + too_long + "; at most " + std::to_string(kMaxRepeatedElements) +
                  " are taken (datagram dropped)");
    return result;
  }
  if (result.unknown_fields > 0) {
    message.DiscardUnknownFields();
    add_error(errors, kErrorUnknownFields,
              type + " carries " + std::to_string(result.unknown_fields) +
                  " field(s) ubersim does not know; they were dropped");
  }
  result.ok = true;
  return result;
}

}  // namespace ubersim::ssl
