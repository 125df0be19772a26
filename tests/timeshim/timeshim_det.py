"""Threads of two processes print to one output (test_timeshim.cpp, deterministic mode).

Three threads of this process and two of a multiprocessing (fork) child each
print 15 lines "name i", 5 at a time between 1 ms sleeps, with CPU work
between lines. Without the shim's deterministic mode the interleaving
depends on the kernel's scheduler and CPython's GIL switch interval; with it
each thread prints its 5 lines in its turn, in a fixed order. Then a
multiprocessing pool (worker processes sharing sem_open locks, a pipe each
way, three threads of its own) maps a function that sleeps.
"""
import multiprocessing
import sys
import threading
import time


def work():
    total = 0
    for k in range(3000):
        total += k
    return total


def lines(name):
    for i in range(15):
        print(f"{name} {i}", flush=True)
        work()
        if i % 5 == 4:
            time.sleep(0.001)


def threads(names):
    started = [threading.Thread(target=lines, args=(name,)) for name in names]
    for thread in started:
        thread.start()
    for thread in started:
        thread.join()


def square_later(x):
    time.sleep(0.01)
    return x * x


def main():
    context = multiprocessing.get_context("fork")
    child = context.Process(target=threads, args=(["d", "e"],))
    child.start()
    threads(["a", "b", "c"])
    child.join()
    with context.Pool(2) as pool:
        print("pool", sum(pool.map(square_later, range(6))), flush=True)
    print(f"end {time.monotonic():.6f}", flush=True)
    return child.exitcode


if __name__ == "__main__":
    sys.exit(main())
