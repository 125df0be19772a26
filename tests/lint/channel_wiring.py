#!/usr/bin/env python3
"""Who publishes and who reads each LCM channel, found in the code.

Scans each program's sources for the typed topics (common/include/ubersim/
topics.hpp) it publishes or subscribes to, and compares the result with the
channel table's lists (`ubersim_channels --wiring`, from common/src/topics.cpp),
so the README's table cannot claim a wiring the code does not have, or miss one.

Usage: channel_wiring.py SOURCE_DIR [UBERSIM_CHANNELS]
Without UBERSIM_CHANNELS it prints what it found, one line per channel,
direction and program (the form `ubersim_channels --wiring` prints).

How a use of `topics::kX` is classified: by the call or the name it is an
argument of, innermost first:
  subscribe(...), subscribe_unhurried(...)                 -> reads
  publish(...)                                             -> publishes
  a variable or member initialised with it: by its type (Publisher<...>: publishes),
    or, when it holds the channel's name (channel_name(...)), by what the file
    does with that name (bus.publish(name, ...) / publish_encoded: publishes;
    subscribe...(name, ...): reads)
  anything else (a channel name in a log line)             -> neither
Two helpers of common/ publish for the programs that use them: SyncClient
(SYNC_CLIENT) and the truth-demand announcer (SIM_TRUTH_DEMAND, through
ProcessHost::ask_for_truth() or a TruthDemandAnnouncer of its own).
"""
import pathlib
import re
import subprocess
import sys

# Program id (as `ubersim_channels --wiring` names it) -> its source folders.
# The DDS bridge carries whichever channels its routes name, both ways, so it
# has no fixed wiring to check (the table says so under its rows).
PROGRAMS = {
    "physics": ["physics/model", "physics/server"],
    "vision_emulator": ["vision_emulator/src", "vision_emulator/include"],
    "radio_emulator": ["radio_emulator/src", "radio_emulator/include"],
    "referee": ["referee/src", "referee/include"],
    "gc_link": ["gc_link/src", "gc_link/include"],
    "ssl_bridge": ["ssl_bridge/src", "ssl_bridge/include"],
    "viewer": ["viewer/src", "viewer/include"],
    "demo_team": ["tools/demo_team"],
    "report": ["tools/report"],
}


def strip_comments_and_strings(text):
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    return re.sub(r'"(\\.|[^"\\\n])*"', '""', text)


def topic_names(root):
    """topics::kX identifier -> the channel base name of its row (a team topic: the yellow one)."""
    header = (root / "common/include/ubersim/topics.hpp").read_text()
    names = {}
    for match in re.finditer(r"Topic<\w+>\s+(k\w+)\{\{?\"(\w+)\"", header):
        names[match.group(1)] = match.group(2)
    return names


def enclosing_names(text, position):
    """The identifiers before each unmatched ( or { around position, innermost first."""
    depth = 0
    names = []
    for i in range(position - 1, -1, -1):
        c = text[i]
        if c in ")}":
            depth += 1
        elif c in "({":
            if depth:
                depth -= 1
                continue
            before = re.search(r"([A-Za-z_]\w*)\s*(<[^;(){}]*>)?\s*$", text[:i])
            names.append(before.group(1) if before else "")
        elif c == ";" and depth == 0:
            break
    return names


def declared_as_publisher(sources, name):
    pattern = r"Publisher<[^;(){}]*>(\s*,\s*\d+\s*>)?\s+" + re.escape(name) + r"\b"
    return any(re.search(pattern, text) for text in sources)


def use_of_name(sources, name):
    """What a file does with a variable holding a channel's name."""
    arg = r"\(\s*" + re.escape(name) + r"\b"
    for text in sources:
        if re.search(r"\bpublish(_encoded)?\s*" + arg, text):
            return "publishes"
        if re.search(r"\bsubscribe\w*\s*(<[^;()]*>)?\s*" + arg, text):
            return "reads"
    return None


def classify(sources, text, position):
    names = enclosing_names(text, position)
    for index, name in enumerate(names):
        if name in ("subscribe", "subscribe_unhurried"):
            return "reads"
        if name in ("publish", "publish_encoded"):
            return "publishes"
        if name in ("", "of", "channel_name", "make_tuple", "array") or name.startswith("std"):
            continue
        if declared_as_publisher(sources, name):
            return "publishes"
        if index > 0 and names[index - 1] == "channel_name":
            return use_of_name(sources, name)
        return None
    return None


def scan(root):
    names = topic_names(root)
    found = set()
    for program, folders in PROGRAMS.items():
        files = [f for d in folders for f in sorted((root / d).rglob("*")) if f.suffix in (".cpp", ".hpp")]
        sources = [strip_comments_and_strings(f.read_text()) for f in files]
        for text in sources:
            for match in re.finditer(r"topics::(k\w+)", text):
                direction = classify(sources, text, match.start())
                if direction and match.group(1) in names:
                    found.add((names[match.group(1)], direction, program))
        joined = "\n".join(sources)
        if re.search(r"\bSyncClient\b", joined):
            found.add(("SYNC_CLIENT", "publishes", program))
        if re.search(r"\bask_for_truth\(|\bTruthDemandAnnouncer\b", joined):
            found.add(("SIM_TRUTH_DEMAND", "publishes", program))
    return found


def main():
    if len(sys.argv) not in (2, 3):
        print(__doc__.splitlines()[0])
        print("usage: channel_wiring.py SOURCE_DIR [UBERSIM_CHANNELS]", file=sys.stderr)
        return 2
    found = scan(pathlib.Path(sys.argv[1]))
    if len(sys.argv) == 2:
        for line in sorted(found):
            print(" ".join(line))
        return 0
    printed = subprocess.run([sys.argv[2], "--wiring"], check=True, capture_output=True, text=True)
    declared = {tuple(line.split()) for line in printed.stdout.splitlines() if line.strip()}
    missing = sorted(found - declared)
    extra = sorted(declared - found)
    for line in missing:
        print("in the code, not in the channel table (common/src/topics.cpp): " + " ".join(line))
    for line in extra:
        print("in the channel table (common/src/topics.cpp), not in the code: " + " ".join(line))
    if missing or extra:
        return 1
    print(f"channel_wiring: the channel table's publishers and readers are the code's ({len(found)} uses)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
