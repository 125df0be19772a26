#!/usr/bin/env python3
"""Generates ubersim/encoded_bounds.hpp from the .lcm files: for each message type a walker
that checks an encoded message before lcm-gen's decode touches it.

Why: lcm-gen's C++ decode resizes every array to the count the bytes claim *before* it
checks that the bytes for those elements are there, so a 435-byte datagram claiming
20,000,000 elements costs ~1 GB. The walker reads only counts and lengths and checks each
against the bytes that are left (count x the smallest encoded size of an element), so a
message that passes cannot make decode allocate more than its own size could hold. It is
derived from the schema at build time, so it cannot drift from the types.

Usage: gen_encoded_bounds.py OUTPUT.hpp a.lcm b.lcm ...
"""
import re
import sys

PRIMITIVE_SIZES = {
    "int8_t": 1, "byte": 1, "boolean": 1, "int16_t": 2, "int32_t": 4, "int64_t": 8,
    "float": 4, "double": 8,
}
INTEGER_TYPES = {"int8_t": 1, "int16_t": 2, "int32_t": 4, "int64_t": 8}
STRING_MIN_SIZE = 5  # int32 length (which counts the terminating NUL) + the NUL itself


class LcmSyntaxError(Exception):
    pass


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", " ", text)


def parse_members(body, where):
    members = []
    for statement in body.split(";"):
        statement = " ".join(statement.split())
        if not statement or statement.startswith("const "):
            continue
        match = re.fullmatch(r"([A-Za-z_][\w.]*)\s+(.+)", statement)
        if not match:
            raise LcmSyntaxError(f"{where}: cannot read member '{statement}'")
        type_name = match.group(1).split(".")[-1]
        for declarator in match.group(2).split(","):
            declarator = declarator.replace(" ", "")
            name_match = re.fullmatch(r"([A-Za-z_]\w*)((?:\[[\w]+\])*)", declarator)
            if not name_match:
                raise LcmSyntaxError(f"{where}: cannot read member '{declarator}'")
            dims = re.findall(r"\[([\w]+)\]", name_match.group(2))
            members.append((type_name, name_match.group(1), dims))
    return members


def parse_file(path):
    with open(path, encoding="utf-8") as f:
        text = strip_comments(f.read())
    structs = {}
    for match in re.finditer(r"struct\s+([A-Za-z_]\w*)\s*\{(.*?)\}", text, flags=re.S):
        structs[match.group(1)] = parse_members(match.group(2), f"{path}: struct {match.group(1)}")
    if not structs:
        raise LcmSyntaxError(f"{path}: no struct found")
    return structs


def min_size(type_name, structs, memo, stack=()):
    if type_name in PRIMITIVE_SIZES:
        return PRIMITIVE_SIZES[type_name]
    if type_name == "string":
        return STRING_MIN_SIZE
    if type_name in memo:
        return memo[type_name]
    if type_name not in structs:
        raise LcmSyntaxError(f"unknown type {type_name}")
    if type_name in stack:
        raise LcmSyntaxError(f"recursive type {type_name}")
    total = 0
    for member_type, _, dims in structs[type_name]:
        element = min_size(member_type, structs, memo, stack + (type_name,))
        fixed = 1
        for dim in dims:
            fixed *= int(dim) if dim.isdigit() else 0  # a variable count may be 0
        total += element * fixed
    memo[type_name] = total
    return total


def walker(type_name, members, structs, memo):
    lines = [f"inline bool walk_{type_name}(Reader& r) {{"]
    counts = {name for _, _, dims in members for name in dims if not name.isdigit()}
    for member_type, name, dims in members:
        if name in counts:
            if member_type not in INTEGER_TYPES or dims:
                raise LcmSyntaxError(f"{type_name}.{name}: an array size must be an integer")
            lines.append(f"  std::int64_t {name} = 0;")
            lines.append(
                f"  if (!r.read_integer({INTEGER_TYPES[member_type]}, {name})) return false;")
            continue
        element = min_size(member_type, structs, memo)
        if not dims:
            if member_type in PRIMITIVE_SIZES:
                lines.append(f"  if (!r.skip({element})) return false;  // {name}")
            elif member_type == "string":
                lines.append(f"  if (!r.skip_string()) return false;  // {name}")
            else:
                lines.append(f"  if (!walk_{member_type}(r)) return false;  // {name}")
            continue
        if element == 0:
            raise LcmSyntaxError(f"{type_name}.{name}: array of a type that can encode in 0 bytes")
        lines.append("  {")
        lines.append(f"    // {name}: every count checked against the bytes left before any loop")
        lines.append("    std::int64_t elements = 1;")
        for dim in dims:
            lines.append(
                f"    if (!r.multiply_count(elements, {dim}, {element})) return false;")
        if member_type in PRIMITIVE_SIZES:
            lines.append(f"    if (!r.skip(elements * {element})) return false;")
        elif member_type == "string":
            lines.append(
                "    for (std::int64_t i = 0; i < elements; ++i) if (!r.skip_string()) return false;")
        else:
            lines.append(
                f"    for (std::int64_t i = 0; i < elements; ++i) if (!walk_{member_type}(r)) "
                "return false;")
        lines.append("  }")
    lines.append("  return true;")
    lines.append("}")
    return "\n".join(lines)


HEADER = """#pragma once
// Generated by lcmtypes/gen_encoded_bounds.py from the .lcm files: do not edit.
// EncodedBounds<Msg>::check(data, size) is true when the bytes hold exactly one
// encoded Msg whose every array count and string length fits in the bytes left,
// so lcm-gen's decode, which allocates before it checks, allocates no more than
// the message could hold. ubersim::decode_bounded (common) is the one caller.
#include <cstddef>
#include <cstdint>
#include <cstring>

{includes}

namespace ubersim::encoded_bounds {{

// Reads big-endian counts and skips fields, never past the end.
class Reader {{
 public:
  Reader(const std::uint8_t* data, std::size_t size)
      : data_(data), left_(static_cast<std::int64_t>(size)) {{}}
  std::int64_t left() const {{ return left_; }}
  bool skip(std::int64_t bytes) {{
    if (bytes < 0 || bytes > left_) return false;
    data_ += bytes;
    left_ -= bytes;
    return true;
  }}
  bool read_integer(int bytes, std::int64_t& value) {{
    if (bytes > left_) return false;
    std::uint64_t raw = 0;
    for (int i = 0; i < bytes; ++i) raw = (raw << 8) | data_[i];
    const int unused_bits = 64 - 8 * bytes;  // sign-extend the narrower types
    value = unused_bits == 0 ? static_cast<std::int64_t>(raw)
                             : static_cast<std::int64_t>(raw << unused_bits) >> unused_bits;
    return skip(bytes);
  }}
  // A string: int32 length counting its NUL, then that many bytes, a C string:
  // no NUL inside and one at the end. lcm-gen's encode measures a string with
  // strlen, so one with a NUL inside would encode shorter than the size it
  // announces, and a process that passes it on (an acknowledgement echoes its
  // sender) would publish a malformed message with uninitialised bytes at its end.
  bool skip_string() {{
    std::int64_t length = 0;
    if (!read_integer(4, length) || length < 1 || length > left_) return false;
    if (data_[length - 1] != 0 || std::memchr(data_, 0, static_cast<std::size_t>(length - 1)) != nullptr) {{
      return false;
    }}
    return skip(length);
  }}
  // elements *= count, refusing a negative count or a product whose smallest
  // encoding (element_min_size bytes each) cannot fit in the bytes left.
  bool multiply_count(std::int64_t& elements, std::int64_t count, std::int64_t element_min_size) const {{
    if (count < 0) return false;
    if (count == 0) {{
      elements = 0;
      return true;
    }}
    if (elements > left_ / element_min_size / count) return false;
    elements *= count;
    return true;
  }}

 private:
  const std::uint8_t* data_;
  std::int64_t left_;
}};

{declarations}

{walkers}

}}  // namespace ubersim::encoded_bounds

namespace ubersim {{

template <class Msg>
struct EncodedBounds;

{traits}

// Every message type of lcmtypes/, for code that must treat them all alike
// (the fuzz target of every type's check and decode, tests).
template <class... Msgs>
struct LcmTypeList {{}};
using AllLcmTypes = LcmTypeList<{type_list}>;

}}  // namespace ubersim
"""

TRAIT = """template <>
struct EncodedBounds<{type}> {{
  static constexpr std::int64_t kMinEncodedSize = 8 + {min_size};  // fingerprint + fields
  static bool check(const void* data, std::size_t size) {{
    encoded_bounds::Reader reader(static_cast<const std::uint8_t*>(data), size);
    std::int64_t fingerprint = 0;
    if (!reader.read_integer(8, fingerprint) ||
        fingerprint != static_cast<std::int64_t>({type}::getHash())) {{
      return false;
    }}
    return encoded_bounds::walk_{type}(reader) && reader.left() == 0;
  }}
}};"""


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    output, paths = argv[1], argv[2:]
    structs = {}
    try:
        for path in paths:
            structs.update(parse_file(path))
        memo = {}
        names = sorted(structs)
        walkers = [walker(name, structs[name], structs, memo) for name in names]
        traits = [TRAIT.format(type=name, min_size=min_size(name, structs, memo)) for name in names]
    except LcmSyntaxError as error:
        print(f"gen_encoded_bounds: {error}", file=sys.stderr)
        return 1
    text = HEADER.format(
        includes="\n".join(f'#include "ubersim/{name}.hpp"' for name in names),
        declarations="\n".join(f"inline bool walk_{name}(Reader& r);" for name in names),
        walkers="\n\n".join(walkers),
        traits="\n\n".join(traits),
        type_list=", ".join(names))
    with open(output, "w", encoding="utf-8") as f:
        f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
