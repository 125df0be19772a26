#!/usr/bin/env python3
"""Listens where grSim does (UDP 20011) and says what a team's software sends there.

A stand-in for grSim's command port, to see what a program sends before anything serves the port:
it decodes grSim_Packet (grSim's src/proto/grSim_Packet.proto, grSim_Commands.proto,
grSim_Replacement.proto) with a small protobuf wire-format reader of its own (no generated code),
and prints one line a second per sender: packets, commands per team, robot ids, the newest
command of each robot, and every replacement.

Usage: grsim_listener.py [--port 20011] [--seconds S] [--address 127.0.0.1]
Exits 0 after S seconds (default: run until interrupted) and prints a total.
"""
import argparse
import socket
import struct
import sys
import time
from collections import defaultdict

# Field numbers from grSim's .proto files (RoboCup-SSL/grSim src/proto/).
PACKET_COMMANDS, PACKET_REPLACEMENT = 1, 2
COMMANDS_TIMESTAMP, COMMANDS_IS_YELLOW, COMMANDS_ROBOT = 1, 2, 3
ROBOT_FIELDS = {1: "id", 2: "kickspeedx", 3: "kickspeedz", 4: "veltangent", 5: "velnormal",
                6: "velangular", 7: "spinner", 8: "wheelsspeed", 9: "wheel1", 10: "wheel2",
                11: "wheel3", 12: "wheel4"}
REPLACEMENT_BALL, REPLACEMENT_ROBOT = 1, 2
BALL_FIELDS = {1: "x", 2: "y", 3: "vx", 4: "vy"}
ROBOT_REPLACEMENT_FIELDS = {1: "x", 2: "y", 3: "dir", 4: "id", 5: "yellowteam", 6: "turnon"}


def varint(data, pos):
    value = shift = 0
    while True:
        if pos >= len(data):
            raise ValueError("truncated varint")
        byte = data[pos]
        pos += 1
        value |= (byte & 0x7F) << shift
        shift += 7
        if not byte & 0x80:
            return value, pos


def fields(data):
    """(number, wire type, value) of each field; length-delimited values as bytes."""
    pos = 0
    while pos < len(data):
        key, pos = varint(data, pos)
        number, wire = key >> 3, key & 7
        if wire == 0:
            value, pos = varint(data, pos)
        elif wire == 1:
            value, pos = struct.unpack_from("<d", data, pos)[0], pos + 8
        elif wire == 5:
            value, pos = struct.unpack_from("<f", data, pos)[0], pos + 4
        elif wire == 2:
            size, pos = varint(data, pos)
            value, pos = data[pos:pos + size], pos + size
        else:
            raise ValueError(f"wire type {wire}")
        yield number, wire, value


def message(data, names):
    return {names.get(n, str(n)): v for n, _, v in fields(data)}


def decode(data):
    """{'commands': {...}, 'replacement': {...}} of one grSim_Packet."""
    out = {}
    for number, _, value in fields(data):
        if number == PACKET_COMMANDS:
            commands = {"robots": []}
            for n, _, v in fields(value):
                if n == COMMANDS_TIMESTAMP:
                    commands["timestamp"] = v
                elif n == COMMANDS_IS_YELLOW:
                    commands["isteamyellow"] = bool(v)
                elif n == COMMANDS_ROBOT:
                    commands["robots"].append(message(v, ROBOT_FIELDS))
            out["commands"] = commands
        elif number == PACKET_REPLACEMENT:
            replacement = {"ball": None, "robots": []}
            for n, _, v in fields(value):
                if n == REPLACEMENT_BALL:
                    replacement["ball"] = message(v, BALL_FIELDS)
                elif n == REPLACEMENT_ROBOT:
                    replacement["robots"].append(message(v, ROBOT_REPLACEMENT_FIELDS))
            out["replacement"] = replacement
    return out


def short(command):
    keys = ("veltangent", "velnormal", "velangular", "kickspeedx", "kickspeedz", "spinner")
    parts = [f"{k}={command[k]:.2f}" if isinstance(command.get(k), float) else f"{k}={command[k]}"
             for k in keys if k in command]
    if command.get("wheelsspeed"):
        wheels = (command.get(f"wheel{i}", 0.0) for i in range(1, 5))
        parts.append("wheels=" + ",".join(f"{w:.1f}" for w in wheels))
    return " ".join(parts)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    parser.add_argument("--port", type=int, default=20011)
    parser.add_argument("--address", default="127.0.0.1")
    parser.add_argument("--seconds", type=float, default=0.0)
    args = parser.parse_args()
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.bind((args.address, args.port))
    sock.settimeout(0.2)
    print(f"grsim_listener: on {args.address}:{args.port}", flush=True)
    start = last = time.monotonic()
    totals = defaultdict(int)
    window = defaultdict(int)
    newest = {}
    while not args.seconds or time.monotonic() - start < args.seconds:
        try:
            data, sender = sock.recvfrom(65536)
        except socket.timeout:
            data = None
        if data is not None:
            totals["packets"] += 1
            window[sender] += 1
            try:
                packet = decode(data)
            except (ValueError, struct.error) as error:
                totals["undecodable"] += 1
                print(f"undecodable datagram from {sender}: {error}", flush=True)
                packet = {}
            commands = packet.get("commands")
            if commands:
                team = "yellow" if commands.get("isteamyellow") else "blue"
                totals[f"{team} commands"] += len(commands["robots"])
                for robot in commands["robots"]:
                    newest[(team, robot.get("id", 0))] = robot
            if packet.get("replacement"):
                totals["replacements"] += 1
                print(f"replacement from {sender}: {packet['replacement']}", flush=True)
        now = time.monotonic()
        if now - last >= 1.0:
            senders = ", ".join(f"{s[0]}:{s[1]} {n}" for s, n in sorted(window.items()))
            print(f"t={now - start:5.1f} s packets/s by sender: {senders or 'none'}", flush=True)
            for (team, robot_id), command in sorted(newest.items()):
                print(f"    {team} {robot_id}: {short(command)}", flush=True)
            window.clear()
            newest.clear()
            last = now
    print("grsim_listener: total " + ", ".join(f"{k} {v}" for k, v in sorted(totals.items())),
          flush=True)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except KeyboardInterrupt:
        sys.exit(0)
