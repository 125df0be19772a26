#!/usr/bin/env python3
"""First-Order-RoboCup-SSL/Utama-Core's runner plays both teams in a synced game, unchanged,
started by ubersim under the time shim (docs/timeshim.md, "Integration with sync mode").

Runs `tools/launch.sh --sync --referee --seed 7 --team both 'UTAMA utama_both_teams.py --seconds
100000' --sync-timeout 120 --duration S` (its --seconds are sim seconds there: it plays until the
game ends), samples ground truth (`ubersim_referee state`) every wall second, and asserts:
  * the run ended by itself at S s of sim time, and no team was dropped;
  * both teams played: at least 3 robots of each moved 0.5 m or more.
It prints game seconds per wall second. S is UBERSIM_INTEROP_SECONDS (default 20; 300 by hand).
With UBERSIM_INTEROP_RERUN=1 it plays the game twice in deterministic mode (--team-deterministic)
and also asserts that both recorded the same bytes on every game channel
(real_program_run.GAME_CHANNELS).

Needs UBERSIM_UTAMA (a python that imports utama_core; setup_real_programs.sh makes
OUT/bin/utama-python); without it exits 77 (skipped) and says why. Run in a network namespace of
its own (tests/run_isolated.sh).

Usage: test_utama_sync.py SOURCE_DIR BUILD_DIR
"""
import os
import shlex
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import real_program_run as run  # noqa: E402
from test_utama import MIN_DISTANCE, MIN_ROBOTS_MOVED  # noqa: E402

# s of wall time per s of sim time before the test gives up: Utama-Core computes about 2 CPU s
# per game s, 5 in deterministic mode (docs/real_programs.md).
WALL_LIMIT_PER_GAME_SECOND = 60


def play_and_check(processes, source_dir, build_dir, utama, seconds, name, log, failures):
    """One game and its checks; returns its ground-truth samples."""
    runner = os.path.join(source_dir, "tests", "interop", "utama_both_teams.py")
    args = ["--referee", "--seed", "7", "--sync-timeout", "120",
            *(["--team-deterministic"] if log else []),
            "--team", "both", f"{shlex.quote(utama)} {shlex.quote(runner)} --seconds 100000"]
    try:
        ubersim, states, wall, status = run.play_synced(
            processes, source_dir, build_dir, name, args, seconds, WALL_LIMIT_PER_GAME_SECOND, log)
    except AssertionError as error:
        failures.append(str(error))
        return []
    print(f"{name}: {seconds:g} s of game in {wall:.1f} s of wall time (Utama-Core's start "
          f"included): {seconds / wall:.3f} game s per wall s")
    if status != 0:
        failures.append(f"{name}: tools/launch.sh exited {status}:\n"
                        + processes.log(name)[-3000:])
    run.check_no_team_dropped(ubersim, failures)
    print(run.game_summary(ubersim.events()))
    return states


def main():
    source_dir, build_dir = sys.argv[1], sys.argv[2]
    utama = run.program_from_env("UBERSIM_UTAMA", "a python that imports Utama-Core's utama_core")
    run.skip_unless_loopback_multicast()
    seconds = run.seconds_to_play(20)
    processes = run.Processes(run.new_folder("ubersim-utama-sync-"))
    failures = []

    def play_one(name, log):
        states = play_and_check(processes, source_dir, build_dir, utama, seconds, name, log,
                                failures)
        for team in ("yellow", "blue"):
            run.check_robots_moved(states, team, MIN_DISTANCE, MIN_ROBOTS_MOVED,
                                   "did Utama-Core's commands reach the radio?", failures)

    run.play_synced_games(processes, build_dir, play_one, failures)
    return run.verdict(failures, processes.folder)


if __name__ == "__main__":
    sys.exit(main())
