#!/usr/bin/env python3
"""ubersim inside the official SSL tournament stack, with the official programs.

Starts ubersim as `tools/launch.sh --referee official` (the SSL bridge with
tracked frames, the official game controller as the referee), the official
ssl-game-controller and ssl-simulation-controller wired as in
RoboCup-SSL/ssl-simulation-setup's docker-compose.yaml, and drives the game
controller through its websocket API with gcctl: every team of the official
robot-specs.yaml by name in NORMAL_FIRST_HALF_PRE (the simulation controller
sends each team's robot specs), Division A, STOP, KICKOFF, NORMAL_START,
BALL_PLACEMENT, HALT. It asserts:
  * the simulation controller logged 0 SimulatorErrors ("SimControl Error");
  * physics plays on the Division A field the simulation controller applied
    (12 m x 9 m, penalty mark 8 m from the attacked goal);
  * 11 robots a side (the simulation controller's robot count is held);
  * the ball lies where the game controller designated it after HALT;
  * the bridge forwarded the game controller's Referee messages to REFEREE.
It prints the counts it measured.

Needs the official binaries: UBERSIM_SSL_GC and UBERSIM_SSL_SIMCTL name them,
UBERSIM_SSL_GCCTL names gcctl (default: beside the game controller). Without
them it exits 77 (skipped) and says why. ../shared/tools/build-official-ssl-stack.sh
builds all three from fetched sources. Run inside a network namespace of its
own (tests/run_isolated.sh): the game controller's websocket port is fixed.

Usage: test_official_stack.py SOURCE_DIR BUILD_DIR
"""
import os
import re
import signal
import subprocess
import sys
import tempfile
import time

SKIP = 77
GC_UI = "127.0.0.1:8081"  # gcctl dials ws://127.0.0.1:8081/api/control
VISION = "224.5.23.2:10020"
TRACKED = "224.5.23.2:10010"
REFEREE = "224.5.23.1:10003"


def skip_unless_official_programs():
    gc = os.environ.get("UBERSIM_SSL_GC", "")
    simctl = os.environ.get("UBERSIM_SSL_SIMCTL", "")
    gcctl = os.environ.get("UBERSIM_SSL_GCCTL") or os.path.join(os.path.dirname(gc), "gcctl")
    for name, path in (("UBERSIM_SSL_GC", gc), ("UBERSIM_SSL_SIMCTL", simctl),
                       ("UBERSIM_SSL_GCCTL", gcctl)):
        if not path or not os.access(path, os.X_OK):
            print(f"SKIP: {name} does not name an executable ('{path}'); build the official "
                  "programs with ../shared/tools/build-official-ssl-stack.sh OUT SRC and set "
                  "UBERSIM_SSL_GC=OUT/bin/ssl-game-controller "
                  "UBERSIM_SSL_SIMCTL=OUT/bin/ssl-simulation-controller")
            sys.exit(SKIP)
    return gc, simctl, gcctl


def skip_unless_loopback_multicast():
    """The official programs receive multicast only on interfaces flagged MULTICAST."""
    link = subprocess.run(["ip", "link", "show", "lo"], capture_output=True, text=True,
                          check=False).stdout
    if "MULTICAST" not in link.split(">")[0]:
        print("SKIP: the loopback interface has no MULTICAST flag, so the official programs hear "
              "nothing on it (run through tests/run_isolated.sh in a network namespace, or "
              "'ip link set lo multicast on')")
        sys.exit(SKIP)


def team_names(robot_specs_yaml):
    """The team names of robot-specs.yaml (its keys two spaces in), 'Unknown' left out."""
    names = re.findall(r'^  "([^"]+)":\s*$', open(robot_specs_yaml, encoding="utf-8").read(),
                       re.MULTILINE)
    return [n for n in names if n != "Unknown"]


class Processes:
    """Children in process groups of their own, all stopped at the end."""

    def __init__(self, folder):
        self.folder = folder
        self.children = []

    def start(self, name, args, cwd=None, stdin=None):
        log = open(os.path.join(self.folder, name + ".log"), "w", encoding="utf-8")
        child = subprocess.Popen(args, cwd=cwd, stdin=stdin, stdout=log, stderr=subprocess.STDOUT,
                                 start_new_session=True, text=True)
        self.children.append((name, child))
        return child

    def log(self, name):
        with open(os.path.join(self.folder, name + ".log"), encoding="utf-8",
                  errors="replace") as f:
            return f.read()

    def stop(self):
        for _, child in reversed(self.children):
            if child.poll() is None:
                os.killpg(child.pid, signal.SIGINT)
        deadline = time.monotonic() + 5
        for _, child in reversed(self.children):
            try:
                child.wait(max(0.1, deadline - time.monotonic()))
            except subprocess.TimeoutExpired:
                os.killpg(child.pid, signal.SIGKILL)
                child.wait()


class GameController:
    """Inputs to the game controller's websocket API, through gcctl's stdin."""

    def __init__(self, processes, gcctl):
        self.gcctl = processes.start("gcctl", [gcctl], stdin=subprocess.PIPE)

    def send(self, json_line, settle=0.5):
        self.gcctl.stdin.write(json_line + "\n")
        self.gcctl.stdin.flush()
        time.sleep(settle)

    def command(self, kind, team="UNKNOWN", settle=1.0):
        self.send('{"change":{"newCommandChange":{"command":{"type":"%s","forTeam":"%s"}}}}'
                  % (kind, team), settle)

    def team_name(self, team, name, settle=0.2):
        self.send('{"change":{"updateTeamStateChange":{"forTeam":"%s","teamName":"%s"}}}'
                  % (team, name), settle)


def referee_tool(build_dir, *args):
    result = subprocess.run([os.path.join(build_dir, "bin", "ubersim_referee"), *args],
                            capture_output=True, text=True, timeout=10, check=False)
    return result.stdout + result.stderr


def wait_for(what, condition, seconds):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        value = condition()
        if value:
            return value
        time.sleep(0.5)
    raise AssertionError(f"timed out after {seconds} s waiting for {what}")


def robots_per_team(state_text):
    return (len(re.findall(r"^\s*yellow\s+\d+", state_text, re.MULTILINE)),
            len(re.findall(r"^\s*blue\s+\d+", state_text, re.MULTILINE)))


def ball_position(state_text):
    found = re.search(r"ball\s+(?:at\s+)?\(?\s*(-?[\d.]+)[ ,]+(-?[\d.]+)", state_text)
    return (float(found.group(1)), float(found.group(2))) if found else None


def main():
    source_dir, build_dir = sys.argv[1], sys.argv[2]
    gc, simctl, gcctl = skip_unless_official_programs()
    skip_unless_loopback_multicast()
    folder = tempfile.mkdtemp(prefix="ubersim-official-stack-")
    specs = os.path.join(source_dir, "tests", "interop", "data", "robot-specs.yaml")
    teams = team_names(specs)
    processes = Processes(folder)
    failures = []
    try:
        env = dict(os.environ, UBERSIM_BUILD_DIR=build_dir)
        launch = subprocess.Popen(
            [os.path.join(source_dir, "tools", "launch.sh"), "--referee", "official",
             "--demo", "both", "--log-dir", os.path.join(folder, "ubersim")],
            stdout=open(os.path.join(folder, "launch.log"), "w", encoding="utf-8"),
            stderr=subprocess.STDOUT, start_new_session=True, env=env)
        processes.children.append(("launch", launch))
        wait_for("ubersim to start", lambda: "Ctrl-C stops everything" in processes.log("launch"),
                 30)
        gc_dir = os.path.join(folder, "gc")
        os.makedirs(gc_dir)
        processes.start("game_controller", [gc, "-visionAddress", VISION, "-trackerAddress",
                                            TRACKED, "-publishAddress", REFEREE, "-address",
                                            GC_UI], cwd=gc_dir)
        processes.start("simulation_controller", [
            simctl, "-refereeAddress", REFEREE, "-visionAddress", VISION, "-trackerAddress",
            TRACKED, "-simControlPort", "10300", "-robotSpecConfig", specs])
        control = GameController(processes, gcctl)
        control.send('{"change":{"updateConfigChange":{"division":"DIV_A"}}}', 1.0)
        # Robot specs go out for each new team name in NORMAL_FIRST_HALF_PRE.
        for i, name in enumerate(teams):
            control.team_name("YELLOW" if i % 2 == 0 else "BLUE", name, settle=1.0)
        control.team_name("YELLOW", teams[0], 0.5)
        control.team_name("BLUE", teams[1], 1.0)
        geometry = wait_for(
            "the Division A geometry in physics",
            lambda: (lambda g: g if re.search(r": 12 x 9 m\b", g) and
                     re.search(r"penalty mark 8 m\b", g) else None)(
                referee_tool(build_dir, "geometry")), 20)
        print("geometry after the simulation controller's config:", geometry.strip())
        counts = wait_for("11 robots a side",
                          lambda: (lambda c: c if c == (11, 11) else None)(
                              robots_per_team(referee_tool(build_dir, "state"))), 30)
        print(f"robots on the field: yellow {counts[0]}, blue {counts[1]}")
        control.command("STOP")
        control.command("KICKOFF", "YELLOW", 2.0)
        control.command("NORMAL_START", settle=4.0)
        control.command("STOP", settle=2.0)
        control.send('{"change":{"setBallPlacementPosChange":{"pos":{"x":1.5,"y":-1.0}}}}', 0.5)
        control.command("BALL_PLACEMENT", "YELLOW", 2.0)
        control.command("HALT", settle=3.0)
        placed = wait_for(
            "the ball at the designated position (1.5, -1.0)",
            lambda: (lambda b: b if b and abs(b[0] - 1.5) < 0.15 and abs(b[1] + 1.0) < 0.15
                     else None)(ball_position(referee_tool(build_dir, "state"))), 15)
        print(f"ball placed by the simulation controller at ({placed[0]:.3f}, {placed[1]:.3f})")
        counts = robots_per_team(referee_tool(build_dir, "state"))
        if counts != (11, 11):
            failures.append(f"robot count not held: yellow {counts[0]}, blue {counts[1]}")
    except AssertionError as e:
        failures.append(str(e))
    finally:
        processes.stop()
    simctl_log = processes.log("simulation_controller")
    errors = [line for line in simctl_log.splitlines() if "SimControl Error" in line]
    specs_sent = simctl_log.count("Sending robot spec")
    print(f"simulation controller: {specs_sent} robot spec messages sent for {len(teams)} team "
          f"names, {len(errors)} SimulatorErrors")
    for line in sorted(set(re.sub(r"^\S+ \S+ ", "", e) for e in errors))[:20]:
        print("  ", line)
    if errors:
        failures.append(f"{len(errors)} SimulatorErrors in the simulation controller's log")
    if specs_sent < len(teams):
        failures.append(f"only {specs_sent} robot spec messages for {len(teams)} team names")
    bridge_log = open(os.path.join(folder, "ubersim", "ssl_bridge.log"), encoding="utf-8",
                      errors="replace").read()
    forwarded = re.search(r"official referee packets forwarded=(\d+)", bridge_log)
    print(f"bridge: {forwarded.group(1) if forwarded else 0} official Referee packets forwarded "
          "to REFEREE")
    if not forwarded or int(forwarded.group(1)) == 0:
        failures.append("the bridge forwarded no Referee message of the game controller")
    if failures:
        print("FAIL:\n  " + "\n  ".join(failures) + f"\n(logs in {folder})")
        return 1
    subprocess.run(["rm", "-rf", folder], check=False)
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
