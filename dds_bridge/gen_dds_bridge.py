#!/usr/bin/env python3
"""Generates the DDS bridge's schema code from the .lcm files, so that every field is written
once, in lcmtypes/*.lcm:

  IDL       ubersim_msgs.idl: one DDS struct per bridged LCM type, ROS 2 naming
            (ubersim_msgs::msg::dds_::<Name>_), LCM's constants as <Name>_Constants modules;
            Cyclone's idlc turns it into the C types.
  HEADER    ubersim/dds_bridge/dds_types.hpp: short C++ names of those C types (DdsVisionFrame)
            and DdsType<T>::descriptor() of each topic type.
  CONVERT   ubersim/dds_bridge/convert.hpp + convert.cpp: to_dds / from_dds of each topic type
            and non_finite_field (the first real number that is NaN/Inf, by its path).
  ROS 2     ros2/ubersim_msgs/msg/<Name>.msg: the same types for a ROS 2 package, comments from
            the .lcm.
The tests reach every field through ubersim/lcm_fields.hpp (lcmtypes/gen_lcm_fields.py).

Mapping rules (the only places a name or type is not carried as it is):
  * type name: camel case without _t (robot_state_t -> RobotState);
  * `num_*` members that give an array's length are the IDL sequence's length;
  * a member named like an IDL keyword gets `_number` (sequence -> sequence_number);
  * LCM boolean (a byte) -> DDS boolean (any non-zero byte reads back as 1);
  * IMPORTED_CONSTANTS: constants a type's field refers to but another .lcm holds.

Usage: gen_dds_bridge.py --out-dir DIR --roots a_t,b_t,... x.lcm y.lcm ...
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "lcmtypes"))
from lcm_schema import LcmSyntaxError, dependency_order, parse_files  # noqa: E402

IDL_TYPES = {
    "int8_t": "int8", "int16_t": "int16", "int32_t": "int32", "int64_t": "int64",
    "float": "float", "double": "double", "boolean": "boolean", "string": "string",
    "byte": "uint8",
}
REALS = {"float", "double"}
INTEGERS = {"int8_t", "int16_t", "int32_t", "int64_t", "byte"}
IDL_KEYWORDS = {"sequence", "module", "struct", "string", "boolean", "const", "enum", "union",
                "default", "case", "switch", "octet", "char", "long", "short", "any", "object"}
# Constants a field names but another type holds: RadioPacket's team is a team_t constant.
IMPORTED_CONSTANTS = {"radio_packet_t": ("team_t", "TEAM_")}
IDL_MODULE = "ubersim_msgs::msg::dds_"
C_PREFIX = "ubersim_msgs_msg_dds__"


def dds_name(lcm_name):
    base = lcm_name[:-2] if lcm_name.endswith("_t") else lcm_name
    return "".join(part.capitalize() for part in base.split("_"))


def idl_member_name(name):
    return name + "_number" if name in IDL_KEYWORDS else name


class Member:
    """One carried member of a struct (counts are folded into their arrays)."""

    def __init__(self, struct, type_name, name, dims, structs):
        self.type, self.name, self.dds = type_name, name, idl_member_name(name)
        self.is_struct = type_name in structs
        where = f"{struct.path}: {struct.name}.{name}"
        if not self.is_struct and type_name not in IDL_TYPES:
            raise LcmSyntaxError(f"{where}: unknown type {type_name}")
        if len(dims) > 1:
            raise LcmSyntaxError(f"{where}: multi-dimensional arrays are not bridged")
        self.fixed = int(dims[0]) if dims and dims[0].isdigit() else None
        self.count = dims[0] if dims and not dims[0].isdigit() else None
        if (self.fixed or self.count) and type_name in ("string", "boolean"):
            raise LcmSyntaxError(f"{where}: arrays of {type_name} are not bridged")
        if self.fixed and self.is_struct:
            raise LcmSyntaxError(f"{where}: fixed arrays of structs are not bridged")


def members_of(struct, structs):
    counts = struct.count_members()
    return [Member(struct, t, n, d, structs) for t, n, d in struct.members if n not in counts]


# ---------------------------------------------------------------- IDL

def all_constants(name, structs):
    """(type, name, value, comment) of a type's constants, imported ones included."""
    struct = structs[name]
    out = [(t, n, v, struct.comments.get(n, "")) for t, n, v in struct.constants]
    if name in IMPORTED_CONSTANTS:
        source, prefix = IMPORTED_CONSTANTS[name]
        out += [(t, prefix + n, v, structs[source].comments.get(n, ""))
                for t, n, v in structs[source].constants]
    return out


def idl_struct(name, structs):
    lines = [f"struct {dds_name(name)}_ {{"]
    for m in members_of(structs[name], structs):
        element = f"{IDL_MODULE}::{dds_name(m.type)}_" if m.is_struct else IDL_TYPES[m.type]
        if m.count:
            lines.append(f"  sequence<{element}> {m.dds};")
        elif m.fixed:
            lines.append(f"  {element} {m.dds}[{m.fixed}];")
        else:
            lines.append(f"  {element} {m.dds};")
    lines.append("};")
    return "\n".join(lines)


def idl_constants(name, structs):
    constants = all_constants(name, structs)
    if not constants:
        return ""
    body = "\n".join(f"  const {IDL_TYPES[t]} {n} = {v};" for t, n, v, _ in constants)
    return f"module {dds_name(name)}_Constants {{\n{body}\n}};\n"


def write_idl(types, structs):
    constants = "".join(idl_constants(name, structs) for name in types)
    bodies = "\n\n".join(idl_struct(name, structs) for name in types)
    return ("// Generated by dds_bridge/gen_dds_bridge.py from lcmtypes/*.lcm: do not edit.\n"
            "// ROS 2's DDS mapping of package ubersim_msgs; fields, units and meaning: the .lcm.\n\n"
            "module ubersim_msgs {\nmodule msg {\n\n"
            f"{constants}\nmodule dds_ {{\n\n{bodies}\n\n}};  // module dds_\n"
            "};  // module msg\n};  // module ubersim_msgs\n")


# ---------------------------------------------------------------- ROS 2 .msg

ROS_TYPES = {
    "int8_t": "int8", "int16_t": "int16", "int32_t": "int32", "int64_t": "int64",
    "float": "float32", "double": "float64", "boolean": "bool", "string": "string",
    "byte": "uint8",
}


def with_comment(text, comment):
    return f"{text}  # {comment}" if comment else text


def write_msg(name, structs):
    struct = structs[name]
    lines = [f"# {struct.doc} (ubersim {name}, lcmtypes/{os.path.basename(struct.path)})"
             if struct.doc else f"# ubersim {name} (lcmtypes/{os.path.basename(struct.path)})"]
    constants = all_constants(name, structs)
    for t, n, v, comment in constants:
        lines.append(with_comment(f"{ROS_TYPES[t]} {n}={v}", comment))
    if constants:
        lines.append("")
    for m in members_of(struct, structs):
        element = dds_name(m.type) if m.is_struct else ROS_TYPES[m.type]
        suffix = "[]" if m.count else f"[{m.fixed}]" if m.fixed else ""
        comment = struct.comments.get(m.name, "")
        if m.dds != m.name:
            comment = f"{comment} (LCM: {m.name})".strip()
        lines.append(with_comment(f"{element}{suffix} {m.dds}", comment))
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------- C++: types

def write_types_header(types, roots):
    aliases = "\n".join(f"using Dds{dds_name(n)} = {C_PREFIX}{dds_name(n)}_;" for n in types)
    traits = "\n".join(
        f"template <>\nstruct DdsType<Dds{dds_name(n)}> : "
        f"DdsTypeWith<&{C_PREFIX}{dds_name(n)}__desc> {{}};" for n in roots)
    return f"""#pragma once
// Generated by dds_bridge/gen_dds_bridge.py from lcmtypes/*.lcm: do not edit.
// The C types idlc generates from the generated ubersim_msgs.idl, under short
// C++ names, and DdsType<T>: the topic descriptor of each topic type.
#include <dds/dds.h>

#include "ubersim_msgs/ubersim_msgs.h"

namespace ubersim::dds {{

{aliases}

template <class T>
struct DdsType;

template <const dds_topic_descriptor_t* Descriptor>
struct DdsTypeWith {{
  static const dds_topic_descriptor_t* descriptor() {{ return Descriptor; }}
}};

{traits}

}}  // namespace ubersim::dds
"""


# ---------------------------------------------------------------- C++: conversions

# How a member is copied, per kind: (LCM -> DDS, DDS -> LCM); {f} is the source
# member, {t} the target, {lcm} / {dds} the element type on each side.
COPY_RULES = {
    "struct sequence": (
        "fill_sequence({t}, {f}, [](const {lcm}& a, {dds}& b) {{ fill_dds(a, b); }});",
        "{t} = from_dds_sequence<{lcm}>({f}, [](const {dds}& a) {{ {lcm} b{{}}; fill_lcm(a, b); "
        "return b; }});"),
    "sequence": ("fill_sequence({t}, {f});", "{t} = from_dds_sequence({f});"),
    "fixed array": ("std::copy(std::begin({f}), std::end({f}), std::begin({t}));",) * 2,
    "struct": ("fill_dds({f}, {t});", "fill_lcm({f}, {t});"),
    "string": ("{t} = dds_string({f});", "{t} = from_dds_string({f});"),
    "boolean": ("{t} = {f} != 0;", "{t} = {f} ? 1 : 0;"),
    "number": ("{t} = {f};",) * 2,
}


def copy_kind(m):
    if m.count:
        return "struct sequence" if m.is_struct else "sequence"
    if m.fixed:
        return "fixed array"
    if m.is_struct:
        return "struct"
    return m.type if m.type in ("string", "boolean") else "number"


def copy_body(name, structs, to_dds):
    lines = []
    for m in members_of(structs[name], structs):
        rule = COPY_RULES[copy_kind(m)][0 if to_dds else 1]
        source, target = (m.name, m.dds) if to_dds else (m.dds, m.name)
        lines.append("  " + rule.format(f=f"from.{source}", t=f"to.{target}", lcm=m.type,
                                        dds=f"Dds{dds_name(m.type)}"))
        if m.count and not to_dds:
            lines.append(f"  to.{m.count} = count_of(to.{m.name});")
    return lines


def has_reals(name, structs, memo):
    if name not in memo:
        memo[name] = any(t in REALS or (t in structs and has_reals(t, structs, memo))
                         for t, _, _ in structs[name].members)
    return memo[name]


def finite_body(name, structs, memo):
    lines = []
    for m in members_of(structs[name], structs):
        path = f'prefix + "{m.name}"'
        if m.is_struct and not has_reals(m.type, structs, memo):
            continue
        if m.is_struct and m.count:
            lines.append(f"  for (std::size_t i = 0; i < message.{m.name}.size(); ++i)")
            lines.append(f'    check_finite(check, element({path}, i) + ".", message.{m.name}[i]);')
        elif m.is_struct:
            lines.append(f'  check_finite(check, {path} + ".", message.{m.name});')
        elif m.type in REALS:
            lines.append(f"  check({path}, message.{m.name});")
    return lines


def write_convert(types, roots, structs):
    memo = {}
    decls = "\n".join(
        f"OwnedSample<Dds{dds_name(n)}> to_dds(const {n}& message);\n"
        f"{n} from_dds(const Dds{dds_name(n)}& sample);\n"
        f"std::string non_finite_field(const {n}& message);" for n in roots)
    includes = "\n".join(f"#include <ubersim/{n}.hpp>" for n in roots)
    header = f"""#pragma once
// Generated by dds_bridge/gen_dds_bridge.py from lcmtypes/*.lcm: do not edit.
// Per bridged topic type: to_dds (an owned DDS sample with every field of the
// LCM message), from_dds (the LCM message of a received sample; num_* counts
// follow the sequences) and non_finite_field ("" when every real number is
// finite, else the path of the first that is not, e.g. "robots[3].body.position[1]").
#include <string>
{includes}

#include "ubersim/dds_bridge/dds_sample.hpp"

namespace ubersim::dds {{

{decls}

}}  // namespace ubersim::dds
"""
    helpers = []
    for n in types:
        d = f"Dds{dds_name(n)}"
        helpers.append(f"void fill_dds(const {n}& from, {d}& to);")
        helpers.append(f"void fill_lcm(const {d}& from, {n}& to);")
        if has_reals(n, structs, memo):
            helpers.append(f"void check_finite(FiniteCheck& check, const std::string& prefix, "
                           f"const {n}& message);")
    bodies = []
    for n in types:
        d = f"Dds{dds_name(n)}"
        bodies.append(f"void fill_dds(const {n}& from, {d}& to) {{\n"
                      + "\n".join(copy_body(n, structs, True)) + "\n}")
        bodies.append(f"void fill_lcm(const {d}& from, {n}& to) {{\n"
                      + "\n".join(copy_body(n, structs, False)) + "\n}")
        if has_reals(n, structs, memo):
            bodies.append(f"void check_finite(FiniteCheck& check, const std::string& prefix, "
                          f"const {n}& message) {{\n" + "\n".join(finite_body(n, structs, memo))
                          + "\n}")
    public = []
    for n in roots:
        d = f"Dds{dds_name(n)}"
        public.append(f"OwnedSample<{d}> to_dds(const {n}& message) {{\n"
                      f"  OwnedSample<{d}> sample;\n  fill_dds(message, sample.get());\n"
                      "  return sample;\n}")
        public.append(f"{n} from_dds(const {d}& sample) {{\n  {n} message{{}};\n"
                      "  fill_lcm(sample, message);\n  return message;\n}")
        check = ('  check_finite(check, "", message);\n' if has_reals(n, structs, memo)
                 else "  static_cast<void>(message);  // no real number in it\n")
        public.append(f"std::string non_finite_field(const {n}& message) {{\n"
                      f"  FiniteCheck check;\n{check}  return check.first();\n}}")
    source = f"""// Generated by dds_bridge/gen_dds_bridge.py from lcmtypes/*.lcm: do not edit.
// NOLINTBEGIN
#include "ubersim/dds_bridge/convert.hpp"

#include <algorithm>
#include <iterator>

#include "ubersim/dds_bridge/finite_check.hpp"

namespace ubersim::dds {{
namespace {{

{chr(10).join(helpers)}

{chr(10).join(chr(10) + b for b in bodies)}

}}  // namespace

{(chr(10) * 2).join(public)}

}}  // namespace ubersim::dds
// NOLINTEND
"""
    return header, source


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out-dir", required=True)
    parser.add_argument("--roots", required=True, help="the topic types, comma-separated")
    parser.add_argument("lcm_files", nargs="+")
    args = parser.parse_args(argv[1:])
    roots = args.roots.split(",")
    try:
        structs = parse_files(args.lcm_files)
        types = dependency_order(structs, roots)
        idl = write_idl(types, structs)
        header, source = write_convert(types, roots, structs)
        types_header = write_types_header(types, roots)
        msgs = {name: write_msg(name, structs) for name in types}
    except LcmSyntaxError as error:
        print(f"gen_dds_bridge: {error}", file=sys.stderr)
        return 1
    out = args.out_dir
    write(os.path.join(out, "idl", "ubersim_msgs", "ubersim_msgs.idl"), idl)
    write(os.path.join(out, "include", "ubersim", "dds_bridge", "dds_types.hpp"), types_header)
    write(os.path.join(out, "include", "ubersim", "dds_bridge", "convert.hpp"), header)
    write(os.path.join(out, "convert.cpp"), source)
    for name, text in msgs.items():
        write(os.path.join(out, "ros2", "ubersim_msgs", "msg", f"{dds_name(name)}.msg"), text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
