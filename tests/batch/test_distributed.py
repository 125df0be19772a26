#!/usr/bin/python3
"""The batch runner on a real Dask cluster on this machine: a scheduler and two
workers as separate processes, the smoke experiment run through them and run
locally, and the results compared. With sync mode in the build (MODE = sync)
every outcome column must be identical; without it (MODE = fast) games depend
on load, and only what does not (games, points, seeds, parameters, status) is.

Usage: test_distributed.py SOURCE_DIR BUILD_DIR
"""
import csv
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time

SOURCE, BUILD = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(SOURCE, "tools", "batch"))
import results as results_module  # noqa: E402

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
            assert run.returncode == 0, f"{name} run failed"
            runs[name] = read(out)

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
