#!/usr/bin/python3
"""The batch runner on a real Dask cluster on this machine: a scheduler and two
workers as separate processes, the smoke experiment run through them and run
locally, and the results compared; then a worker SIGKILLed in the middle of a
game: the game's processes die with it, and the game, rescheduled, writes into
a fresh folder. With sync mode in the build (MODE = sync)
every outcome column must be identical; without it (MODE = fast) games depend
on load, and only what does not (games, points, seeds, parameters, status) is.

Usage: test_distributed.py SOURCE_DIR BUILD_DIR
"""
import csv
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

SOURCE, BUILD = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(SOURCE, "tools", "batch"))
import results as results_module  # noqa: E402
from live_processes import processes_mentioning  # noqa: E402

BATCH = os.path.join(SOURCE, "tools", "ubersim_batch")
PYTHON = "/usr/bin/python3"


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def has_sync(build):
    """Sync mode with the referee holding physics: games reproducible."""
    out = subprocess.run([os.path.join(build, "bin", "ubersim_physics"), "--help"],
                         capture_output=True, text=True).stdout
    return "--sync-referee" in out


def read(out_dir):
    with open(os.path.join(out_dir, "results.csv")) as f:
        return list(csv.DictReader(f))


def alive(pid):
    """Running (not gone, not a zombie waiting to be reaped)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rpartition(")")[2].split()[0] != "Z"
    except OSError:
        return False


def check_killed_worker(folder, address, mode):
    """SIGKILL the worker that runs a game, mid-game: no process of that game
    may survive, and the scheduler's second attempt of the game must write into
    a folder of its own, which results.csv names."""
    experiment = os.path.join(folder, "one.cfg")
    with open(experiment, "w") as f:
        f.write(f"""SCENARIO = division_b_6v6
VISION_PROFILE = cmdragons02
RADIO_PROFILE = cmdragons02
GAME = division_b
GAME_LENGTH = 150
GAMES_PER_POINT = 1
SEED = 1
YELLOW = demo
BLUE = demo
MODE = {mode}
GAME_TIMEOUT = 120
""")
    out = os.path.join(folder, "killed")
    first = os.path.join(out, "games", "0000") + "/"  # not 0000-attempt2/
    batch = subprocess.Popen([BATCH, "run", experiment, "--out", out, "--build-dir", BUILD, "-q",
                              "--scheduler", address],
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        deadline = time.monotonic() + 60
        while not any("ubersim_demo_team" in c and "--team blue" in c
                      for c in processes_mentioning(first).values()):
            assert time.monotonic() < deadline and batch.poll() is None, \
                f"the game did not start: {processes_mentioning(first)}"
            time.sleep(0.1)
        time.sleep(1.0)  # mid-game
        game = processes_mentioning(first)
        drivers = [pid for pid, c in game.items() if "game.py" in c and "spec.json" in c]
        assert len(drivers) == 1, game
        with open(f"/proc/{drivers[0]}/stat") as f:
            worker = int(f.read().rpartition(")")[2].split()[1])  # the driver's parent
        with open(f"/proc/{worker}/cmdline", "rb") as f:
            assert b"python" in f.read(), f"the driver's parent {worker} is not a Dask worker"
        assert os.path.exists(os.path.join(out, "games", "0000", "physics.log"))
        assert not os.path.exists(os.path.join(out, "games", "0000", "result.json")), \
            "the game ended before its worker was killed: make it longer"
        os.kill(worker, signal.SIGKILL)
        print(f"test_distributed: SIGKILLed Dask worker {worker} in the middle of game 0 "
              f"({len(game)} processes)")
        # The game would run for several more seconds: its processes must die
        # with the worker, not when the game ends.
        deadline = time.monotonic() + 3
        while (processes_mentioning(first) or any(map(alive, game))) \
                and time.monotonic() < deadline:
            time.sleep(0.1)
        left = processes_mentioning(first)
        left.update({pid: game[pid] for pid in game if alive(pid)})
        assert not left, "processes of the killed worker's game outlived it:\n" + \
            "\n".join(f"{pid}: {c}" for pid, c in left.items())
        output, _ = batch.communicate(timeout=240)
        print(output)
        # 4: the game finished degraded (a sync client dropped on a loaded
        # machine): still a finished second attempt, which is what this checks.
        assert batch.returncode in (0, 4), \
            f"the batch after the lost worker: status {batch.returncode}"
    finally:
        if batch.poll() is None:
            batch.kill()
    (row,) = read(out)
    assert row["status"] in ("ok", "degraded"), row
    if row["status"] == "degraded":
        print(f"test_distributed: note: the second attempt finished degraded: {row['reason']}")
    assert row["log_dir"] != first.rstrip("/"), \
        f"the rescheduled game wrote into the killed attempt's folder {row['log_dir']}"
    assert os.path.exists(os.path.join(row["log_dir"], "result.json")), row["log_dir"]
    assert not os.path.exists(os.path.join(out, "games", "0000", "result.json")), \
        "something wrote a result into the killed attempt's folder"
    print(f"test_distributed: the killed worker's game left no process; its second attempt "
          f"finished in {row['log_dir']}")


def main():
    try:
        import distributed  # noqa: F401
    except ImportError:
        print("test_distributed: SKIPPED: python3-distributed is not installed "
              "(tools/install-deps.sh installs it)")
        return 77
    folder = tempfile.mkdtemp(prefix="ubersim-dask-test-")
    processes = []
    ok = False
    try:
        mode = "sync" if has_sync(BUILD) else "fast"
        with open(os.path.join(SOURCE, "config", "experiments", "smoke.cfg")) as f:
            text = f.read()
        lines = [line for line in text.splitlines() if not line.startswith("MODE")]
        experiment = os.path.join(folder, "smoke.cfg")
        with open(experiment, "w") as f:
            f.write("\n".join(lines) + f"\nMODE = {mode}\n")

        port = free_port()
        address = f"tcp://127.0.0.1:{port}"
        log = open(os.path.join(folder, "cluster.log"), "w")
        processes.append(subprocess.Popen(
            [PYTHON, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
             "--port", str(port), "--dashboard-address", ":0"],
            stdout=log, stderr=subprocess.STDOUT, cwd=folder))
        for n in range(2):
            processes.append(subprocess.Popen(
                [PYTHON, "-m", "distributed.cli.dask_worker", address, "--nthreads", "1",
                 "--nworkers", "1", "--dashboard-address", ":0", "--name", f"worker-{n}",
                 "--local-directory", os.path.join(folder, f"worker-{n}")],
                stdout=log, stderr=subprocess.STDOUT, cwd=folder))
        from distributed import Client
        deadline = time.monotonic() + 60
        while True:
            try:
                with Client(address, timeout=5) as client:
                    if len(client.scheduler_info()["workers"]) == 2:
                        break
            except OSError:
                pass
            if time.monotonic() > deadline:
                raise AssertionError("the Dask cluster did not come up (see cluster.log)")
            time.sleep(0.5)

        runs = {}
        for name, extra in (("dask", ["--scheduler", address]), ("local", [])):
            out = os.path.join(folder, name)
            run = subprocess.run([BATCH, "run", experiment, "--out", out, "--build-dir", BUILD,
                                  "-q", *extra], capture_output=True, text=True, timeout=600)
            print(run.stdout + run.stderr)
            runs[name] = read(out) if os.path.exists(os.path.join(out, "results.csv")) else []
            # A game whose sync client was dropped (it did not answer within
            # --sync-timeout of wall time) is another game: say so, not only
            # that some column differs.
            degraded = [r for r in runs[name] if r["status"] == "degraded"]
            assert not degraded, f"{name} run: a sync client was dropped, so these games " \
                f"cannot equal the other run's: " + \
                "; ".join(f"game {r['game']}: {r['reason']}" for r in degraded)
            assert run.returncode == 0, f"{name} run failed"

        dask_rows, local_rows = runs["dask"], runs["local"]
        assert len(dask_rows) == len(local_rows) == 4, (len(dask_rows), len(local_rows))
        compared = ["game", "point", "seed", "vision.LATENCY", "status"]
        if mode == "sync":
            compared += results_module.GAME_OUTCOME_COLUMNS + ["event_types"]
        for d, l in zip(dask_rows, local_rows):
            for column in compared:
                assert d[column] == l[column], f"game {d['game']}: {column}: dask {d[column]} " \
                                               f"!= local {l[column]}"
        # The games really ran on the workers: their drivers came from the uploaded file.
        with open(os.path.join(folder, "dask", "games", "0000", "driver.log")) as f:
            f.read()
        print(f"test_distributed: {len(dask_rows)} games on 2 Dask workers equal the local run "
              f"in {', '.join(compared)}" + ("" if mode == "sync" else
                                             " (no sync mode in this build: scores not compared)"))
        check_killed_worker(folder, address, mode)
        ok = True
        return 0
    finally:
        for p in reversed(processes):
            p.terminate()
        for p in processes:
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                p.kill()
        if ok:
            shutil.rmtree(folder, ignore_errors=True)
        else:
            print(f"test_distributed: kept {folder}")


if __name__ == "__main__":
    sys.exit(main())
