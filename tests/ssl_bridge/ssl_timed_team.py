#!/usr/bin/env python3
"""An SSL team in Python written the way real team software is, for the time
shim (docs/timeshim.md, "Integration with sync mode"): standard library only,
no answer per frame. A receiver thread reads SSL-Vision packets from the
multicast group with a socket timeout; a worker process (multiprocessing)
turns the packet count into a speed; the main loop runs at its own 50 Hz
(time.sleep to the next deadline on time.monotonic), sends one RobotControl
per loop on its team's port (hand-encoded protobuf) and reads responses with
select. Each loop prints its clocks:
    loop N monotonic S.SSSSSSSSS time W.WWWWWW packets P
  ssl_timed_team.py --team yellow|blue [--vision-port 10020] [--port 10301|10302]
"""
import argparse
import multiprocessing
import select
import signal
import socket
import struct
import sys
import threading
import time


def varint(value):
    out = bytearray()
    while True:
        byte = value & 0x7F
        value >>= 7
        if value:
            out.append(byte | 0x80)
        else:
            out.append(byte)
            return bytes(out)


def field(number, payload):
    """A length-delimited protobuf field."""
    return varint(number << 3 | 2) + varint(len(payload)) + payload


def robot_control(robot_ids, forward, angular):
    """RobotControl: each robot moves with local velocity (forward, 0, angular)."""
    velocity = b"".join(struct.pack("<Bf", tag, value)
                        for tag, value in ((0x0D, forward), (0x15, 0.0), (0x1D, angular)))
    commands = b""
    for robot_id in robot_ids:
        command = varint(1 << 3) + varint(robot_id) + field(2, field(2, velocity))
        commands += field(1, command)
    return commands


def speed_worker(requests, answers):
    """A child process: a speed from the number of packets seen."""
    for packets in iter(requests.get, None):
        answers.put(min(1.0, 0.1 + packets / 200.0))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--team", choices=("yellow", "blue"), required=True)
    parser.add_argument("--vision-port", type=int, default=10020)
    parser.add_argument("--port", type=int, default=0)
    args = parser.parse_args()
    port = args.port or (10302 if args.team == "yellow" else 10301)
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())

    vision = socket.socket(socket.AF_INET, socket.SOCK_DGRAM, socket.IPPROTO_UDP)
    vision.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    vision.bind(("224.5.23.2", args.vision_port))
    membership = socket.inet_aton("224.5.23.2") + socket.inet_aton("127.0.0.1")
    vision.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP, membership)
    vision.settimeout(0.25)
    robots = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    robots.connect(("127.0.0.1", port))

    seen = {"packets": 0}
    lock = threading.Lock()

    def receive():
        while not stop.is_set():
            try:
                vision.recv(65536)
            except socket.timeout:
                continue
            with lock:
                seen["packets"] += 1

    receiver = threading.Thread(target=receive, daemon=True)
    receiver.start()
    requests, answers = multiprocessing.Queue(), multiprocessing.Queue()
    worker = multiprocessing.Process(target=speed_worker, args=(requests, answers))
    worker.start()

    period = 0.02
    next_loop = time.monotonic()
    loop = 0
    responses = 0
    while not stop.is_set():
        with lock:
            packets = seen["packets"]
        requests.put(packets)
        forward = answers.get()
        robots.send(robot_control(range(3), forward, 0.5))
        while select.select([robots], [], [], 0)[0]:
            robots.recv(65536)
            responses += 1
        print(f"loop {loop} monotonic {time.monotonic():.9f} time {time.time():.6f} "
              f"packets {packets}", flush=True)
        loop += 1
        next_loop += period
        time.sleep(max(0.0, next_loop - time.monotonic()))
    requests.put(None)
    worker.join()
    print(f"ssl_timed_team.py {args.team}: {loop} loops, {responses} responses", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
