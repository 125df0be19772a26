#!/usr/bin/env python3
"""First-Order-RoboCup-SSL/Utama-Core plays both teams on ubersim through the SSL protocols.

Starts ubersim as `tools/launch.sh --ssl-bridge --referee` (SSL-Vision on 224.5.23.2:10020, the
simulation protocol on 127.0.0.1:10300-10302, ubersim's automatic referee on 224.5.23.1:10003),
then Utama-Core's own StrategyRunner in its grsim mode with a strategy per team
(utama_both_teams.py: 6 robots a side, the network referee). It samples ground truth
(`ubersim_referee state`, from SIM_STATE) every second for UBERSIM_INTEROP_SECONDS (default 20;
300 by hand) and asserts:
  * Utama-Core saw the field: its runner got past its own checks (geometry equal to its
    configured field, every expected robot and the ball seen) within 90 s;
  * both teams played under Utama-Core's control: while the referee's command was a running one
    (no placement), at least 3 robots of each team moved 0.5 m or more;
  * no team dropped: the radio emulator received robot commands from each team at 5 Hz or more
    over the run, and Utama-Core was still running at the end.
It prints what happened in the game (goals, fouls, referee events, distances, command rates).

Needs UBERSIM_UTAMA: a python that imports utama_core (setup_real_programs.sh makes
OUT/bin/utama-python). Without it exits 77 (skipped) and says why. Run in a network namespace of
its own (tests/run_isolated.sh).

Usage: test_utama.py SOURCE_DIR BUILD_DIR
"""
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import real_program_run as run  # noqa: E402

MIN_ROBOTS_MOVED = 3
MIN_DISTANCE = 0.5  # m per robot while the game runs
MIN_COMMAND_RATE = 5.0  # RobotControl datagrams per second per team


def main():
    source_dir, build_dir = sys.argv[1], sys.argv[2]
    utama = run.program_from_env("UBERSIM_UTAMA", "a python that imports Utama-Core's utama_core")
    run.skip_unless_loopback_multicast()
    seconds = run.seconds_to_play(20)
    folder = run.new_folder("ubersim-utama-")
    processes = run.Processes(folder)
    failures = []
    states, events, received = [], [], {}
    sending = 0.0  # wall seconds Utama-Core ran its loop
    try:
        ubersim = run.Ubersim(processes, source_dir, build_dir)
        runner = os.path.join(source_dir, "tests", "interop", "utama_both_teams.py")
        launched = time.monotonic()
        processes.start("utama", [utama, runner, "--seconds", str(seconds + 30)])
        if not processes.wait_for_line("utama", "utama: running", 90):
            raise AssertionError("Utama-Core did not get past its start checks in 90 s:\n"
                                 + processes.log("utama")[-3000:])
        started = time.monotonic()
        print(f"Utama-Core saw the field and both teams {started - launched:.1f} s after its start")

        def still_running():
            if processes.children["utama"].poll() is not None:
                raise AssertionError("Utama-Core stopped:\n" + processes.log("utama")[-3000:])

        states = run.sample_states(ubersim, seconds, still_running)
        still_running()
        processes.stop("utama")
        sending = time.monotonic() - started
        processes.stop("launch", 10)
        events = ubersim.events()
        received = ubersim.radio_received()
    except AssertionError as error:
        failures.append(str(error))
    finally:
        processes.stop_all()
    print(run.game_summary(events))
    run.print_ball_motion(states)
    played = states[-1]["t"] - states[0]["t"] if len(states) > 1 else 0.0
    for team in ("yellow", "blue"):
        moved = run.print_team_motion(states, events, team)
        if sum(1 for d in moved.values() if d >= MIN_DISTANCE) < MIN_ROBOTS_MOVED and states:
            failures.append(f"{team}: fewer than {MIN_ROBOTS_MOVED} robots moved {MIN_DISTANCE} m "
                            "in play")
        rate = received.get(team, 0) / max(sending, 1.0)
        print(f"{team}: {received.get(team, 0)} robot commands received by the radio emulator "
              f"(about {rate:.0f} per s)")
        if rate < MIN_COMMAND_RATE and not failures:
            failures.append(f"{team}: robot commands at {rate:.1f} per s, below "
                            f"{MIN_COMMAND_RATE} (team dropped?)")
    print(f"sampled {len(states)} states over {played:.1f} s of sim time")
    return run.verdict(failures, folder)


if __name__ == "__main__":
    sys.exit(main())
