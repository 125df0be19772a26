#!/usr/bin/env python3
"""grSim's own Qt sample client (RoboCup-SSL/grSim clients/qt) moves a robot on ubersim.

Starts ubersim as `tools/launch.sh --ssl-bridge` (grSim's command port 127.0.0.1:20011 on the
bridge; no referee, whose placements would move the robot), the client under Xvfb, and drives
its window with xdotool as a user would, with the keyboard only (the dialog's focus chain
starts at "Simulator Address"; Shift+Tab from there reaches its last button, "Connect"): Id 0,
Yellow (its default), Velocity X 1 m/s, Connect, Send. The client then sends a grSim_Packet
every 20 ms. It asserts that yellow robot 0 covers 0.5 m
or more in the 3 s after Send (ground truth, `ubersim_referee state`), then presses Reset (the
client sends zeros once and stops sending) and asserts that the robot, from 1 s later on, stays
within 0.05 m for 1 s.

grSim's sample client has no ball placement (grSim_Replacement comes from grSim's own window
and from teams' software); docs/real_programs.md says how to place the ball on ubersim.

Needs UBERSIM_GRSIM_QT_CLIENT (setup_real_programs.sh's OUT/bin/grsim-qt-client), Xvfb and
xdotool. Without them exits 77 (skipped) and says why. Run in a network namespace of its own
(tests/run_isolated.sh).

Usage: test_grsim_qt_client.py SOURCE_DIR BUILD_DIR
"""
import math
import os
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import real_program_run as run  # noqa: E402

WINDOW = "grSim Sample Client"
MIN_DISTANCE = 0.5  # m in 3 s at 1 m/s commanded
MAX_DRIFT_STOPPED = 0.05  # m in 1 s, from 1 s after the zero command on


def start_xvfb(processes):
    """Xvfb on a free display (it picks one and writes its number); the DISPLAY value."""
    read_end, write_end = os.pipe()
    log = open(os.path.join(processes.folder, "xvfb.log"), "w", encoding="utf-8")
    xvfb = subprocess.Popen(["Xvfb", "-displayfd", str(write_end), "-nolisten", "tcp",
                             "-screen", "0", "1024x768x24"], pass_fds=(write_end,),
                            stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
    processes.children["xvfb"] = xvfb
    os.close(write_end)
    with os.fdopen(read_end) as f:
        number = f.readline().strip()
    if not number:
        raise AssertionError("Xvfb did not start:\n" + processes.log("xvfb"))
    return ":" + number


def xdotool(display, *args):
    result = subprocess.run(["xdotool", *args], env=dict(os.environ, DISPLAY=display),
                            capture_output=True, text=True, timeout=10, check=False)
    return result.stdout.strip()


def client_window(display, seconds=30):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        found = xdotool(display, "search", "--name", WINDOW)
        if found:
            return found.split()[0]
        time.sleep(0.5)
    raise AssertionError(f"no window named '{WINDOW}' in {seconds} s")


def keys(display, window, *names):
    for name in names:
        xdotool(display, "key", "--window", window, "--clearmodifiers", name)
        time.sleep(0.15)


def drive_client(display, window):
    """Velocity X 1 m/s for yellow robot 0, then Connect and Send, with the keyboard."""
    xdotool(display, "windowfocus", "--sync", window)
    keys(display, window, "Tab", "Tab", "Tab", "ctrl+a")  # Address -> Port -> Id -> Velocity X
    xdotool(display, "type", "--window", window, "1")
    keys(display, window, "shift+Tab", "shift+Tab", "shift+Tab", "shift+Tab", "space")  # Connect
    keys(display, window, "shift+Tab", "shift+Tab", "space")  # Connect -> Reset -> Send


def reset_client(display, window):
    keys(display, window, "Tab", "space")  # Send -> Reset


def robot_position(ubersim):
    state = ubersim.state()
    return state["yellow"].get(0) if state else None


def main():
    source_dir, build_dir = sys.argv[1], sys.argv[2]
    client = run.program_from_env("UBERSIM_GRSIM_QT_CLIENT", "grSim's Qt sample client")
    for tool in ("Xvfb", "xdotool"):
        if not shutil.which(tool):
            run.skip(f"{tool} not found (Debian: apt-get install xvfb xdotool)")
    run.skip_unless_loopback_multicast()
    folder = run.new_folder("ubersim-grsim-qt-client-")
    processes = run.Processes(folder)
    failures = []
    try:
        ubersim = run.Ubersim(processes, source_dir, build_dir, referee=False)
        display = start_xvfb(processes)
        processes.start("client", [client], env=dict(os.environ, DISPLAY=display,
                                                     QT_QPA_PLATFORM="xcb"))
        window = client_window(display)
        start = robot_position(ubersim)
        drive_client(display, window)
        time.sleep(3.0)
        end = robot_position(ubersim)
        reset_client(display, window)
        time.sleep(1.0)
        stopped = robot_position(ubersim)
        time.sleep(1.0)
        still = robot_position(ubersim)
        if None in (start, end, stopped, still):
            raise AssertionError("yellow robot 0 is not on the field")
        moved = math.dist(start, end)
        print(f"yellow 0 moved {moved:.2f} m in 3 s: ({start[0]:.2f}, {start[1]:.2f}) -> "
              f"({end[0]:.2f}, {end[1]:.2f}); after Reset {math.dist(stopped, still):.3f} m in 1 s")
        if moved < MIN_DISTANCE:
            failures.append(f"yellow 0 moved {moved:.2f} m, expected {MIN_DISTANCE} m or more "
                            "(does the bridge serve grSim's protocol on UDP 20011?)")
        if math.dist(stopped, still) > MAX_DRIFT_STOPPED:
            failures.append(f"yellow 0 moved {math.dist(stopped, still):.3f} m in the second "
                            f"after Reset's zero command, more than {MAX_DRIFT_STOPPED} m")
    except AssertionError as error:
        failures.append(str(error))
    finally:
        processes.stop_all()
    return run.verdict(failures, folder)


if __name__ == "__main__":
    sys.exit(main())
