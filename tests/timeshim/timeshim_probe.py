"""A Python team-like program for the time shim's tests (test_timeshim.cpp).

Uses what CPython's standard library waits with: time.sleep, time.time and
time.monotonic, select.select, selectors (epoll), a socket timeout, a thread
waiting on threading.Event with a timeout, and a multiprocessing child. Prints
"label seconds" lines: the sim times it saw.
"""
import multiprocessing
import select
import selectors
import socket
import sys
import threading
import time


def say(label, value):
    print(f"{label} {value:.6f}", flush=True)


def child(queue):
    time.sleep(0.75)
    queue.put(time.monotonic())


def main():
    say("start", time.monotonic())
    time.sleep(1.0)
    say("sleep", time.monotonic())
    say("time", time.time())
    reader, _ = socket.socketpair()
    select.select([reader], [], [], 0.5)
    say("select", time.monotonic())
    with selectors.DefaultSelector() as selector:
        selector.register(reader, selectors.EVENT_READ)
        selector.select(0.25)
    say("selector", time.monotonic())
    udp = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    udp.bind(("127.0.0.1", 0))
    udp.settimeout(2.0)
    try:
        udp.recv(16)
    except socket.timeout:
        say("socket_timeout", time.monotonic())
    event = threading.Event()
    seen = []
    waiter = threading.Thread(target=lambda: seen.append((event.wait(1.5), time.monotonic())))
    waiter.start()
    time.sleep(0.5)
    say("main_while_waiting", time.monotonic())
    waiter.join()
    say("event_wait", seen[0][1])
    queue = multiprocessing.get_context("fork").Queue()
    process = multiprocessing.get_context("fork").Process(target=child, args=(queue,))
    process.start()
    say("child", queue.get())
    process.join()
    say("end", time.monotonic())
    return 0


if __name__ == "__main__":
    sys.exit(main())
