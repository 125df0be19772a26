#!/usr/bin/env python3
"""project-neon/NeonFC-SSL, one process per colour, plays a synced game unchanged under the time
shim, on grSim's protocol (docs/timeshim.md, "Team programs that speak grSim's protocol").

Runs `tools/launch.sh --sync --referee --team yellow 'grsim:NEONFC -p YELLOW' --team blue
'grsim:NEONFC -p BLUE' --duration S` (each NeonFC in a folder of its own, for its ./logs; the
configs setup_real_programs.sh wrote) with a charge for NeonFC's polling layers
(--team-charge-us 50 --team-yield-after-ms 10) and 60 s of wall time before a team that keeps
physics waiting is dropped (--sync-timeout 60: on a loaded machine the group's step between two
frames can take longer than 1 s), samples ground truth (`ubersim_referee state`)
every wall second while it plays, and asserts:
  * the run ended by itself at S s of sim time, and no team was dropped;
  * the bridge stamped grSim commands of both colours (its `grSim radio packets COLOUR (timed)`
    counts), and no grSim command was dropped;
  * both teams played: at least 3 robots of each moved 0.5 m or more (in the whole game: in
    its first seconds NeonFC places its robots for the kick-off).
It prints game seconds per wall second. S is UBERSIM_INTEROP_SECONDS (default 10; 300 by hand);
UBERSIM_INTEROP_CHARGE_US sets the charge (default 50; a larger one plays faster and polls less).
With UBERSIM_INTEROP_RERUN=1 it plays the game twice in deterministic mode (--team-deterministic,
--seed 3) and also asserts that both recorded the same bytes on every game channel
(real_program_run.GAME_CHANNELS).

Needs UBERSIM_NEONFC and the two configs (UBERSIM_NEONFC_CONFIGS), as test_neonfc.py; without
them exits 77 (skipped) and says why. Run in a network namespace of its own
(tests/run_isolated.sh).

Usage: test_neonfc_sync.py SOURCE_DIR BUILD_DIR
"""
import os
import re
import shlex
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import real_program_run as run  # noqa: E402
from test_neonfc import COLOURS, MIN_DISTANCE, MIN_ROBOTS_MOVED, configs  # noqa: E402

WALL_LIMIT_PER_GAME_SECOND = 40  # s of wall time per s of sim time before the test gives up


def team_command(neonfc, config, folder):
    os.makedirs(os.path.join(folder, "logs"))
    return f"grsim:cd {shlex.quote(folder)} && exec {shlex.quote(neonfc)} -p {shlex.quote(config)}"


def play(processes, source_dir, build_dir, neonfc, config_of, seconds, name, log=None):
    charge = os.environ.get("UBERSIM_INTEROP_CHARGE_US", "50")
    args = ["--referee", "--seed", "3", "--team-charge-us", charge, "--team-yield-after-ms", "10",
            "--sync-timeout", "60", *(["--team-deterministic"] if log else [])]
    for colour in COLOURS:
        folder = os.path.join(processes.folder, name, f"neonfc_{colour}")
        args += ["--team", colour, team_command(neonfc, config_of[colour], folder)]
    return run.play_synced(processes, source_dir, build_dir, name, args, seconds,
                           WALL_LIMIT_PER_GAME_SECOND, log)


def check_logs(ubersim, failures):
    run.check_no_team_dropped(ubersim, failures)
    bridge = ubersim.log("ssl_bridge.log")
    for colour in COLOURS:
        stamped = re.search(rf"grSim radio packets {colour} \(timed\)=(\d+)", bridge)
        print(f"{colour}: {stamped.group(1) if stamped else 0} grSim radio packets stamped")
        if not stamped:
            failures.append(f"no grSim command of {colour} was stamped by the bridge")
    if "grSim command packets dropped" in bridge:
        failures.append("the bridge dropped grSim commands: "
                        + ", ".join(re.findall(r"grSim command packets dropped[^=]*=\d+", bridge)))
    for line in bridge.splitlines():
        if "timeshim:" in line:
            print(f"bridge: {line}")


def play_and_check(processes, source_dir, build_dir, neonfc, config_of, seconds, name, log,
                   failures):
    """One game, its checks; returns its ground-truth samples and referee events."""
    try:
        ubersim, states, wall, status = play(processes, source_dir, build_dir, neonfc, config_of,
                                             seconds, name, log)
    except AssertionError as error:
        failures.append(str(error))
        return [], []
    print(f"{name}: {seconds:g} s of game in {wall:.1f} s of wall time (NeonFC's start "
          f"included): {seconds / wall:.2f} game s per wall s")
    if status != 0:
        failures.append(f"{name}: tools/launch.sh exited {status}:\n"
                        + processes.log(name)[-3000:])
    check_logs(ubersim, failures)
    return states, ubersim.events()


def main():
    source_dir, build_dir = sys.argv[1], sys.argv[2]
    neonfc = run.program_from_env("UBERSIM_NEONFC", "NeonFC-SSL's main (OUT/bin/neonfc)")
    config_of = configs(neonfc)
    run.skip_unless_loopback_multicast()
    seconds = run.seconds_to_play(10)
    processes = run.Processes(run.new_folder("ubersim-neonfc-sync-"))
    failures = []

    def play_one(name, log):
        states, events = play_and_check(processes, source_dir, build_dir, neonfc, config_of,
                                        seconds, name, log, failures)
        print(run.game_summary(events))
        for team in COLOURS:
            run.print_team_motion(states, events, team)
            run.check_robots_moved(states, team, MIN_DISTANCE, MIN_ROBOTS_MOVED,
                                   "did NeonFC's grSim commands reach the radio?", failures)

    run.play_synced_games(processes, build_dir, play_one, failures)
    return run.verdict(failures, processes.folder)


if __name__ == "__main__":
    sys.exit(main())
