"""What the interop tests with real team software share: ubersim started with tools/launch.sh,
the programs in process groups of their own, ground truth sampled with `ubersim_referee state`,
and what the run's logs say (referee events, radio and bridge counts).

The tests run inside a network namespace of their own (tests/run_isolated.sh): the SSL ports are
fixed and the programs join SSL multicast groups.
"""
import json
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

SKIP = 77
RUNNING_COMMANDS = ("NORMAL_START", "FORCE_START", "DIRECT_FREE_YELLOW", "DIRECT_FREE_BLUE")


def skip(reason):
    print(f"SKIP: {reason}", flush=True)
    sys.exit(SKIP)


def program_from_env(variable, what):
    """The executable an environment variable names, or a skip that says how to get it."""
    path = os.environ.get(variable, "")
    if not path or not os.access(path, os.X_OK):
        skip(f"{variable} does not name an executable ('{path}'): {what}. Set it up with "
             "tests/interop/setup_real_programs.sh SRC_ROOT OUT (docs/real_programs.md) and set "
             f"{variable} as it prints")
    return path


def skip_unless_loopback_multicast():
    link = subprocess.run(["ip", "link", "show", "lo"], capture_output=True, text=True,
                          check=False).stdout
    if "MULTICAST" not in link.split(">")[0]:
        skip("the loopback interface has no MULTICAST flag: run through tests/run_isolated.sh "
             "(a network namespace of its own)")


def seconds_to_play(default):
    return float(os.environ.get("UBERSIM_INTEROP_SECONDS", default))


class Processes:
    """Children in process groups of their own, logging to FOLDER/NAME.log, stopped at the end."""

    def __init__(self, folder):
        self.folder = folder
        self.children = {}

    def start(self, name, args, cwd=None, env=None):
        log = open(os.path.join(self.folder, name + ".log"), "w", encoding="utf-8")
        child = subprocess.Popen(args, cwd=cwd or self.folder, env=env, stdin=subprocess.DEVNULL,
                                 stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        self.children[name] = child
        return child

    def log(self, name):
        path = os.path.join(self.folder, name + ".log")
        if not os.path.exists(path):
            return ""
        with open(path, encoding="utf-8", errors="replace") as f:
            return re.sub(r"\x1b\[[0-9;]*[A-Za-z]", "", f.read())

    def wait_for_line(self, name, text, seconds):
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            if text in self.log(name):
                return True
            if self.children[name].poll() is not None:
                return text in self.log(name)
            time.sleep(0.25)
        return False

    def stop(self, name, seconds=5.0):
        """SIGINT to the group, then SIGKILL after SECONDS; the exit code.

        Descendants that left the group (NeonFC runs under script(1), in a session of its own)
        and outlive the child are killed too.
        """
        child = self.children[name]
        others = descendants(child.pid)
        if child.poll() is None:
            try:
                os.killpg(child.pid, signal.SIGINT)
            except ProcessLookupError:
                pass
        try:
            code = child.wait(seconds)
        except subprocess.TimeoutExpired:
            os.killpg(child.pid, signal.SIGKILL)
            code = child.wait()
        for pid in others:
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        return code

    def stop_all(self):
        for name in reversed(list(self.children)):
            self.stop(name)


def descendants(pid):
    """Every process below PID now, from /proc."""
    parents = {}
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat", encoding="utf-8") as f:
                    parents[int(entry)] = int(f.read().rsplit(")", 1)[1].split()[1])
            except (OSError, IndexError, ValueError):
                pass
    found, frontier = [], [pid]
    while frontier:
        below = [p for p, parent in parents.items() if parent in frontier]
        found += below
        frontier = below
    return found


class Run:
    """A run of tools/launch.sh with its process logs in LOG_DIR: ground truth, logs, events."""

    def __init__(self, build_dir, log_dir):
        self.build_dir = build_dir
        self.log_dir = log_dir

    def state(self):
        """{'t': sim time, 'ball': (x, y), 'yellow': {id: (x, y)}, 'blue': {...}} or None."""
        result = subprocess.run([os.path.join(self.build_dir, "bin", "ubersim_referee"), "state"],
                                capture_output=True, text=True, timeout=10, check=False)
        return parse_state(result.stdout)

    def log(self, name):
        path = os.path.join(self.log_dir, name)
        if not os.path.exists(path):
            return ""
        with open(path, encoding="utf-8", errors="replace") as f:
            return f.read()

    def events(self):
        return [json.loads(line) for line in self.log("events.jsonl").splitlines() if line.strip()]

    def radio_received(self):
        """{team: packets the radio emulator received} from its summary at stop."""
        found = re.findall(r"\] (yellow|blue) \(profile [^)]*\): received (\d+)",
                           self.log("radio.log"))
        return {team: int(n) for team, n in found}


class Ubersim(Run):
    """tools/launch.sh with the SSL bridge (and the automatic referee), and its ground truth."""

    def __init__(self, processes, source_dir, build_dir, referee=True):
        super().__init__(build_dir, os.path.join(processes.folder, "ubersim"))
        self.processes = processes
        env = dict(os.environ, UBERSIM_BUILD_DIR=build_dir)
        processes.start("launch", [os.path.join(source_dir, "tools", "launch.sh"), "--ssl-bridge",
                                   *(["--referee"] if referee else []), "--log-dir",
                                   self.log_dir], env=env)
        if not processes.wait_for_line("launch", "Ctrl-C stops everything", 60):
            raise AssertionError("ubersim did not start:\n" + processes.log("launch"))


# What a synced game records that must be the same bytes on a rerun with the same seeds
# (docs/timeshim.md, "Deterministic mode"); the rest (schedules, horizons, repeats) follows wall
# time.
GAME_CHANNELS = ("VISION", "RADIO_YELLOW", "RADIO_BLUE", "RADIO_FEEDBACK_YELLOW",
                 "RADIO_FEEDBACK_BLUE", "SIM_STATE", "SIM_COMMANDS", "REFEREE")


def rerun_wanted():
    """UBERSIM_INTEROP_RERUN=1: play the synced game twice in deterministic mode and compare."""
    return os.environ.get("UBERSIM_INTEROP_RERUN") == "1"


def play_synced(processes, source_dir, build_dir, name, launch_args, seconds, wall_per_second,
                log=None):
    """tools/launch.sh --sync LAUNCH_ARGS --duration SECONDS (process logs in FOLDER/NAME, the LCM
    log in LOG if given), ground truth sampled every wall second. Returns (Run, states, wall s,
    exit status); an AssertionError when it does not end within 60 + WALL_PER_SECOND x SECONDS s
    of wall time."""
    log_dir = os.path.join(processes.folder, name)
    args = [os.path.join(source_dir, "tools", "launch.sh"), "--sync", "--duration",
            f"{seconds:g}", "--log-dir", log_dir, *(["--log", log] if log else []), *launch_args]
    started = time.monotonic()
    launch = processes.start(name, args, env=dict(os.environ, UBERSIM_BUILD_DIR=build_dir))
    ubersim = Run(build_dir, log_dir)
    states = []
    deadline = started + 60 + wall_per_second * seconds
    while launch.poll() is None and time.monotonic() < deadline:
        state = ubersim.state()
        if state:
            states.append(state)
        time.sleep(1)
    wall = time.monotonic() - started
    if launch.poll() is None:
        processes.stop(name, 10)
        raise AssertionError(f"the game did not end within {wall:.0f} s of wall time:\n"
                             + processes.log(name)[-3000:])
    return ubersim, states, wall, launch.returncode


def check_no_team_dropped(ubersim, failures):
    radio = ubersim.log("radio.log")
    if "sync: no client was dropped" not in radio:
        failures.append("a team was dropped: "
                        + "; ".join(re.findall(r"sync client dropped: [^\n]*", radio)[:2]))


def compare_reruns(build_dir, first_log, second_log, failures):
    """ubersim_log_compare over GAME_CHANNELS: each channel's verdict printed, a failure for each
    that differs."""
    result = subprocess.run([os.path.join(build_dir, "bin", "ubersim_log_compare"),
                             "--channels", "^(" + "|".join(GAME_CHANNELS) + ")$", first_log,
                             second_log], capture_output=True, text=True, check=False)
    print("rerun, the game channels:\n" + result.stdout.strip())
    differing = [line for line in result.stdout.splitlines() if "DIFFERENT" in line]
    if result.returncode not in (0, 1) or not result.stdout.strip():
        failures.append(f"ubersim_log_compare failed ({result.returncode}): {result.stderr[-500:]}")
    failures.extend(f"the rerun differs: {line}" for line in differing)


def moved_per_robot(states, team):
    """m each robot of TEAM travelled between the samples, by id."""
    moved = {}
    for before, after in zip(states, states[1:]):
        for robot, (x, y) in after[team].items():
            if robot in before[team]:
                x0, y0 = before[team][robot]
                moved[robot] = moved.get(robot, 0.0) + ((x - x0) ** 2 + (y - y0) ** 2) ** 0.5
    return moved


def check_robots_moved(states, team, min_distance, min_robots, why, failures):
    """Prints how far each robot of TEAM moved; a failure (saying WHY it may be) unless at least
    MIN_ROBOTS moved MIN_DISTANCE m."""
    moved = moved_per_robot(states, team)
    print(f"{team}: m moved in the game per robot "
          + (", ".join(f"{i}: {d:.1f}" for i, d in sorted(moved.items())) or "none"))
    if sum(1 for d in moved.values() if d >= min_distance) < min_robots:
        failures.append(f"{team}: fewer than {min_robots} robots moved {min_distance} m ({why})")


def play_synced_games(processes, build_dir, play_one, failures):
    """PLAY_ONE(name, log) once ("game", no LCM log); with UBERSIM_INTEROP_RERUN=1 twice ("game",
    "rerun", each with an LCM log, which tells PLAY_ONE to play in deterministic mode), then the
    game channels of both compared. The processes are stopped at the end."""
    rerun = rerun_wanted()
    games = ["game", "rerun"] if rerun else ["game"]
    logs = [os.path.join(processes.folder, f"{name}.lcm") if rerun else None for name in games]
    try:
        for name, log in zip(games, logs):
            play_one(name, log)
    finally:
        processes.stop_all()
    if rerun:
        compare_reruns(build_dir, logs[0], logs[1], failures)


def parse_state(text):
    time_match = re.search(r"sim time ([-\d.e+]+) s", text)
    if not time_match:
        return None
    state = {"t": float(time_match.group(1)), "yellow": {}, "blue": {}, "ball": None}
    ball = re.search(r"^ball ([-\d.e+]+) ([-\d.e+]+)", text, re.MULTILINE)
    if ball:
        state["ball"] = (float(ball.group(1)), float(ball.group(2)))
    for team, robot_id, x, y in re.findall(r"^(yellow|blue) (\d+) \S+ ([-\d.e+]+) ([-\d.e+]+)",
                                            text, re.MULTILINE):
        state[team][int(robot_id)] = (float(x), float(y))
    return state


def sample_states(ubersim, seconds, watch=None, every=1.0):
    """Ground truth every EVERY s for SECONDS s; WATCH() may raise to end early."""
    states = []
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        state = ubersim.state()
        if state:
            states.append(state)
        if watch:
            watch()
        time.sleep(every)
    return states


def command_at(events, t):
    command = None
    for event in events:
        if "command" in event and event["t"] <= t:
            command = event["command"]
    return command


def distance_in_play(states, events, team):
    """{robot id: m it moved between samples with the same running command all along}.

    Only intervals in which the referee's command was a running one (normal or forced start, a
    direct free kick) and did not change count: the referee places robots only at stoppages, so
    what moved then was moved by the team's commands (or pushed by a robot that was).
    """
    changes = [e["t"] for e in events if "command" in e]
    moved = {}
    for before, after in zip(states, states[1:]):
        command = command_at(events, before["t"])
        if command not in RUNNING_COMMANDS:
            continue
        if any(before["t"] < t <= after["t"] for t in changes):
            continue
        for robot_id, (x, y) in after[team].items():
            if robot_id in before[team]:
                x0, y0 = before[team][robot_id]
                moved[robot_id] = moved.get(robot_id, 0.0) + math.hypot(x - x0, y - y0)
    return moved


def speeds_by_command(states, events, team):
    """{referee command: mean speed (m/s) of TEAM's robots between samples under it}, so a run
    shows whether the team obeys STOP (at most 1.5 m/s) and HALT (still)."""
    changes = [e["t"] for e in events if "command" in e]
    totals = {}
    for before, after in zip(states, states[1:]):
        dt = after["t"] - before["t"]
        if dt <= 0 or any(before["t"] < t <= after["t"] for t in changes):
            continue
        command = command_at(events, before["t"]) or "none"
        for robot_id, (x, y) in after[team].items():
            if robot_id in before[team]:
                x0, y0 = before[team][robot_id]
                distance, time_sum = totals.get(command, (0.0, 0.0))
                totals[command] = (distance + math.hypot(x - x0, y - y0), time_sum + dt)
    return {command: d / t for command, (d, t) in totals.items() if t > 0}


def print_team_motion(states, events, team):
    """Distances in play per robot and mean speeds per referee command; the distances."""
    moved = distance_in_play(states, events, team)
    print(f"{team}: m moved in play per robot "
          + (", ".join(f"{i}: {d:.1f}" for i, d in sorted(moved.items())) or "none"))
    speeds = speeds_by_command(states, events, team)
    print(f"{team}: mean robot speed by referee command "
          + (", ".join(f"{c} {v:.2f} m/s" for c, v in sorted(speeds.items())) or "none"))
    return moved


def print_ball_motion(states):
    """How far the ball went and its longest stillness (under 0.1 m in all that time)."""
    balls = [(s["t"], s["ball"]) for s in states if s["ball"]]
    travelled = sum(math.dist(a, b) for (_, a), (_, b) in zip(balls, balls[1:]))
    longest, since = 0.0, 0
    for i, (t, (x, y)) in enumerate(balls):
        x0, y0 = balls[since][1]
        if math.hypot(x - x0, y - y0) >= 0.1:
            since = i
        longest = max(longest, t - balls[since][0])
    print(f"ball: {travelled:.1f} m travelled between samples; longest still {longest:.0f} s"
          + (f"; last at ({balls[-1][1][0]:.2f}, {balls[-1][1][1]:.2f})" if balls else ""))


def game_summary(events):
    """Goals, fouls, commands and the last result line of the referee's event log, as text."""
    goals = [e for e in events if e.get("event") in ("GOAL", "POSSIBLE_GOAL")]
    fouls = [e for e in events if e.get("foul")]
    kinds = {}
    for e in events:
        if "event" in e:
            kinds[e["event"]] = kinds.get(e["event"], 0) + 1
    result = next((e for e in reversed(events) if "result" in e), None)
    lines = [f"referee: {len(goals)} goals, {len(fouls)} fouls; events "
             + (", ".join(f"{k} {n}" for k, n in sorted(kinds.items())) or "none")]
    if result:
        lines.append("referee result: " + json.dumps(result))
    return "\n".join(lines)


def verdict(failures, folder):
    """Prints the test's verdict; returns its exit status (the folder stays on a failure)."""
    if failures:
        print("FAIL:\n  " + "\n  ".join(failures) + f"\n(logs in {folder})")
        return 1
    remove_unless_kept(folder)
    print("PASS")
    return 0


def remove_unless_kept(folder):
    """A passed run's logs go, unless UBERSIM_INTEROP_KEEP_LOGS=1."""
    if os.environ.get("UBERSIM_INTEROP_KEEP_LOGS") == "1":
        print(f"logs kept in {folder}")
    else:
        shutil.rmtree(folder, ignore_errors=True)


def new_folder(prefix):
    return tempfile.mkdtemp(prefix=prefix, dir=os.environ.get("TMPDIR"))
