#!/usr/bin/env python3
"""project-neon/NeonFC-SSL, one process per colour, plays a refereed game on ubersim with grSim's
protocol.

Starts ubersim as `tools/launch.sh --ssl-bridge --referee` (the bridge: SSL-Vision geometry on
224.5.23.2:10020, tracked frames on 224.5.23.2:10010, grSim commands on 127.0.0.1:20011;
ubersim's automatic referee on 224.5.23.1:10003), then NeonFC-SSL twice, unchanged, each with
its config file (setup_real_programs.sh writes config_yellow.toml and config_blue.toml: ports,
addresses, colour and side only). It samples ground truth (`ubersim_referee state`) every second
for UBERSIM_INTEROP_SECONDS (default 30; 300 by hand) and asserts:
  * both NeonFC processes started their five layers (they saw geometry and opened their grSim
    socket) and were still running at the end;
  * both teams played under NeonFC's control: while the referee's command was a running one (no
    placement), at least 3 robots of each team moved 0.5 m or more; NeonFC commands robots only
    with grSim_Packet on UDP 20011, so this fails when nothing serves grSim's protocol there;
  * the referee's game went on: at least one NORMAL_START or FORCE_START.
It prints what happened in the game (goals, fouls, referee events, distances).

Needs UBERSIM_NEONFC (setup_real_programs.sh's OUT/bin/neonfc) and the two configs
(UBERSIM_NEONFC_CONFIGS, default OUT/neonfc beside it). Without them exits 77 (skipped) and says
why. Run in a network namespace of its own (tests/run_isolated.sh).

Usage: test_neonfc.py SOURCE_DIR BUILD_DIR
"""
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import real_program_run as run  # noqa: E402

COLOURS = ("yellow", "blue")
MIN_ROBOTS_MOVED = 3
MIN_DISTANCE = 0.5  # m per robot while the game runs
STARTED = "Layer OutputLayer started"


def configs(neonfc):
    folder = os.environ.get("UBERSIM_NEONFC_CONFIGS") or os.path.join(
        os.path.dirname(os.path.dirname(os.path.abspath(neonfc))), "neonfc")
    paths = {c: os.path.join(folder, f"config_{c}.toml") for c in COLOURS}
    for path in paths.values():
        if not os.path.isfile(path):
            run.skip(f"no NeonFC config {path} (UBERSIM_NEONFC_CONFIGS names the folder that "
                     "setup_real_programs.sh filled)")
    return paths


def start_teams(processes, neonfc, config_of):
    launched = time.monotonic()
    for colour in COLOURS:
        cwd = os.path.join(processes.folder, f"neonfc_{colour}")
        os.makedirs(os.path.join(cwd, "logs"))
        processes.start(f"neonfc_{colour}", [neonfc, "-p", config_of[colour]], cwd=cwd)
    for colour in COLOURS:
        if not processes.wait_for_line(f"neonfc_{colour}", STARTED, 90):
            raise AssertionError(f"NeonFC {colour} did not start its layers in 90 s:\n"
                                 + processes.log(f"neonfc_{colour}")[-3000:])
    print(f"NeonFC started both colours' layers {time.monotonic() - launched:.1f} s after "
          "their start")


def main():
    source_dir, build_dir = sys.argv[1], sys.argv[2]
    neonfc = run.program_from_env("UBERSIM_NEONFC", "NeonFC-SSL's main (OUT/bin/neonfc)")
    config_of = configs(neonfc)
    run.skip_unless_loopback_multicast()
    seconds = run.seconds_to_play(30)
    folder = run.new_folder("ubersim-neonfc-")
    processes = run.Processes(folder)
    failures = []
    states, events = [], []
    try:
        ubersim = run.Ubersim(processes, source_dir, build_dir)
        start_teams(processes, neonfc, config_of)

        def still_running():
            for colour in COLOURS:
                if processes.children[f"neonfc_{colour}"].poll() is not None:
                    raise AssertionError(f"NeonFC {colour} stopped:\n"
                                         + processes.log(f"neonfc_{colour}")[-3000:])

        states = run.sample_states(ubersim, seconds, still_running)
        still_running()
        for colour in COLOURS:
            processes.stop(f"neonfc_{colour}")
        processes.stop("launch", 10)
        events = ubersim.events()
        grsim_lines = [line for line in ubersim.log("ssl_bridge.log").splitlines()
                       if "grsim" in line.lower() and "summary" in line.lower()]
        print("\n".join(grsim_lines) or "bridge: no grSim summary line in ssl_bridge.log")
    except AssertionError as error:
        failures.append(str(error))
    finally:
        processes.stop_all()
    print(run.game_summary(events))
    run.print_ball_motion(states)
    for team in COLOURS:
        moved = run.print_team_motion(states, events, team)
        if states and sum(1 for d in moved.values() if d >= MIN_DISTANCE) < MIN_ROBOTS_MOVED:
            failures.append(f"{team}: fewer than {MIN_ROBOTS_MOVED} robots moved {MIN_DISTANCE} m "
                            "in play (does the bridge serve grSim's protocol on UDP 20011?)")
    if states and not any(e.get("command") in ("NORMAL_START", "FORCE_START") for e in events):
        failures.append("the referee never started play")
    print(f"sampled {len(states)} states over "
          f"{(states[-1]['t'] - states[0]['t']) if len(states) > 1 else 0:.1f} s of sim time")
    return run.verdict(failures, folder)


if __name__ == "__main__":
    sys.exit(main())
