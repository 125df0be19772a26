#!/usr/bin/env python3
"""Speed of the Python module against the C++ physics bench, in one run (docs/python.md).

Steps per second (25 ms steps) of one world for 2 x 6 and 2 x 11 robots, with
and without vision and radio emulation, and of VectorSim with 1, 2 and 4
worlds; beside them the C++ bench's figure for the World alone
(ubersim_physics_bench --only world: the same scenes, jointed wheels), turned
into 25 ms steps per second. The machine may be shared: only the ratios of
one run mean anything.

    PYTHONPATH=build/python /usr/bin/python3 python/bench/bench_python.py \
        --physics-bench build/bin/ubersim_physics_bench

With --rsim DIR (a folder holding rSim's robosim package, built by hand from
robocin/rSim with Debian's ODE and pybind11) it runs rSim's SSL the same way.
"""

import argparse
import math
import os
import re
import subprocess
import sys
import time

import numpy as np

import ubersim

STEP = 0.025
SCENES = {"2x6": "division_b_6v6", "2x11": "division_a_11v11"}


def weave_table(robots, count=160):
    """Commands for every robot at `count` instants: each weaves on its own phase."""
    table = []
    for k in range(count):
        rows = ubersim.commands(len(robots))
        t = STEP * k
        for i, robot in enumerate(robots):
            phase = 0.7 * i
            rows[i, 0:2] = robot[0:2]
            rows[i, 3:6] = (1.5 * math.cos(0.8 * t + phase), 1.5 * math.sin(1.1 * t + 2 * phase),
                            2.0 * math.sin(0.5 * t + phase))
        table.append(rows)
    return table


def sim_rate(scenario, seconds, emulated):
    profiles = dict(vision_profile="cmdragons02", radio_profile="cmdragons02") if emulated else {}
    sim = ubersim.Sim(scenario=scenario, seed=1, **profiles)
    table = weave_table(sim.reset()["robots"])
    steps = int(round(seconds / STEP))
    start = time.perf_counter()
    for k in range(steps):
        sim.step(table[k % len(table)])
    return steps / (time.perf_counter() - start)


def vector_rate(n, scenario, seconds, threads):
    """(world steps per wall second, CPU seconds per wall second) of n worlds."""
    sims = ubersim.VectorSim(n, scenario=scenario, seed=1, threads=threads)
    table = weave_table(sims.reset()["robots"][0])
    steps = int(round(seconds / STEP))
    start, cpu = time.perf_counter(), time.process_time()
    for k in range(steps):
        sims.step([table[k % len(table)]] * n)
    wall = time.perf_counter() - start
    return n * steps / wall, (time.process_time() - cpu) / wall


def best(repeat, measure, *args):
    """The fastest of `repeat` runs: the one least disturbed by the machine's other work."""
    return max(measure(*args) for _ in range(repeat))


def cpp_rates(bench, seconds, repeat):
    """25 ms steps per second of the C++ World alone, by scene (its own best of `repeat`)."""
    out = subprocess.run([bench, "--only", "world", "--models", "jointed", "--repeat", str(repeat),
                          "--seconds", str(seconds), "--scenarios", *SCENES.values()],
                         capture_output=True, text=True, check=True).stdout
    rates = {}
    for name, scenario in SCENES.items():
        match = re.search(rf"^{scenario}\s+\S+\s+jointed\s+\S+\s+(\S+)", out, re.M)
        if not match:
            raise RuntimeError(f"no figure for {scenario} in:\n{out}")
        rates[name] = float(match.group(1)) / STEP  # sim s per wall s -> 25 ms steps per s
    return rates


def rsim_rate(folder, n_per_team, field_type, seconds):
    if folder not in sys.path:
        sys.path.insert(0, folder)
    import robosim  # noqa: E402  (rSim, built by hand)

    blue = [[-0.3 * (i + 1), 0.1 * i, 0] for i in range(n_per_team)]
    yellow = [[0.3 * (i + 1), 0.1 * i, 180] for i in range(n_per_team)]
    sim = robosim.SSL(field_type, n_per_team, n_per_team, int(STEP * 1000), [0, 0, 0, 0], blue,
                      yellow)
    actions = []
    for k in range(160):
        t = STEP * k
        rows = np.zeros((2 * n_per_team, 8))
        for i in range(2 * n_per_team):
            rows[i, 1:4] = (1.5 * math.cos(0.8 * t + 0.7 * i), 1.5 * math.sin(1.1 * t + 1.4 * i),
                            2.0 * math.sin(0.5 * t + 0.7 * i))
        actions.append(rows)
    steps = int(round(seconds / STEP))
    start = time.perf_counter()
    for k in range(steps):
        sim.step(actions[k % len(actions)])
        sim.get_state()
    return steps / (time.perf_counter() - start)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--physics-bench", required=True, help="path of ubersim_physics_bench")
    parser.add_argument("--seconds", type=float, default=20.0, help="sim seconds per figure")
    parser.add_argument("--repeat", type=int, default=3, help="runs of each; the fastest counts")
    parser.add_argument("--rsim", help="folder holding rSim's robosim package (optional)")
    options = parser.parse_args()
    cores = len(os.sched_getaffinity(0))
    print(f"ubersim Python benchmark: 25 ms steps per second, {options.seconds:g} s of sim time "
          f"each, best of {options.repeat}, {cores} cores, load average "
          f"{os.getloadavg()[0]:.2f} at start")
    cpp = cpp_rates(options.physics_bench, options.seconds, options.repeat)
    print(f"\n{'one world':34s} {'steps/s':>9s} {'vs C++':>7s}")
    for name, scenario in SCENES.items():
        print(f"  C++ World alone, {name:14s} {cpp[name]:9.0f} {1.0:7.2f}")
        for emulated in (False, True):
            rate = best(options.repeat, sim_rate, scenario, options.seconds, emulated)
            label = f"Sim {name}" + (", vision + radio" if emulated else "")
            print(f"  {label:32s} {rate:9.0f} {rate / cpp[name]:7.2f}")
        if options.rsim:
            per_team = {"2x6": (6, 1), "2x11": (11, 0)}[name]
            rate = best(options.repeat, rsim_rate, options.rsim, per_team[0], per_team[1],
                        options.seconds)
            print(f"  {'rSim ' + name:32s} {rate:9.0f} {rate / cpp[name]:7.2f}")
    print(f"\n{'VectorSim 2x6, threads = min(n, cores)':40s} {'world steps/s':>13s} "
          f"{'vs 1 world':>10s}")
    single = None
    for n in (1, 2, 4):
        rate, busy = best(options.repeat, vector_rate, n, SCENES["2x6"], options.seconds, 0)
        single = single or rate
        print(f"  {n} world{'s' if n > 1 else ' '}{'':31s} {rate:13.0f} {rate / single:10.2f}"
              f"   (CPU s per wall s: {busy:.2f})")
    print(f"load average at the end: {os.getloadavg()[0]:.2f}")
    print("\nvs C++: the Sim's rate over the C++ World's in this run (target >= 0.8 without "
          "emulation);\nvs 1 world: VectorSim's world steps per second over one world's "
          "(target >= 1.7 for 2 worlds on 2 cores).\n"
          "CPU s per wall s: how many cores the process got; on a machine busy with other work "
          "(and\nLinux's autogroup scheduling, which shares the CPU by session) it caps VectorSim.")


if __name__ == "__main__":
    main()
