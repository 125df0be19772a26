"""One game: an isolated ubersim process set under the automatic referee.

execute_game(spec) is what the local pool and the Dask workers call: it starts
this module as a driver process of its own (in a network namespace of its own
when the machine allows one, else on an LCM port of its own), and returns the
driver's result. run_driver(spec) is that driver: it writes the game's config
overlay, starts physics, the emulators, both teams and the referee, waits for
the referee to end the game, stops everything and reads the event log.
"""
import ctypes
import json
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import threading
import time

DEMO = "{bin}/ubersim_demo_team --lcm-url {lcm_url} --config-dir {config_dir} --team {team} {sync}"
STOP_GRACE = 2.0  # s between SIGTERM and SIGKILL

_running = {}  # driver pid -> Popen, so that Ctrl-C can stop every game
_running_lock = threading.Lock()

PR_SET_PDEATHSIG = 1
PARENT_ENV = "UBERSIM_BATCH_PARENT"  # pid the driver must die with
try:
    _libc = ctypes.CDLL(None, use_errno=True)
except OSError:  # no C library to call: children then outlive a killed parent
    _libc = None


def die_with_parent():
    """This process gets SIGKILL when the thread that started it exits, even
    when that thread's process is SIGKILLed (prctl PR_SET_PDEATHSIG). Called in
    the child between fork and exec (preexec_fn): no allocation, no lock."""
    if _libc is not None:
        _libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)


def namespaces_available():
    """True when this user may create a network namespace (unshare -rn)."""
    if shutil.which("unshare") is None or shutil.which("ip") is None:
        return False
    for flags in (["-n"], ["-rn"]):
        if subprocess.run(["unshare", *flags, "true"], capture_output=True).returncode == 0:
            return True
    return False


def _unshare_flags():
    return ["-n"] if subprocess.run(["unshare", "-n", "true"],
                                    capture_output=True).returncode == 0 else ["-rn"]


def claim_game_dir(game_dir):
    """A folder of this attempt's own: game_dir, or, when an earlier attempt of
    the same game (on a worker that was lost) made that one, game_dir-attempt2,
    -attempt3, ... mkdir is atomic, so two copies of a game never share one."""
    parent = os.path.dirname(game_dir)
    os.makedirs(parent, exist_ok=True)
    attempt = 1
    while True:
        path = game_dir if attempt == 1 else f"{game_dir}-attempt{attempt}"
        try:
            os.mkdir(path)
            return path
        except FileExistsError:
            attempt += 1


def execute_game(spec):
    """Runs one game in a driver process; returns its result dict.

    The driver and every process of the game belong to the caller: they run
    in a process group of their own (Ctrl-C stops the group), and each gets
    SIGKILL when its parent dies (PR_SET_PDEATHSIG), so a Dask worker killed
    mid-game takes its game with it; the scheduler's next attempt of the game
    writes into a fresh folder (claim_game_dir), named in its result."""
    spec = dict(spec, game_dir=claim_game_dir(spec["game_dir"]))
    game_dir = spec["game_dir"]
    spec_path = os.path.join(game_dir, "spec.json")
    with open(spec_path, "w") as f:
        json.dump(spec, f, indent=1)
    driver = [sys.executable, os.path.abspath(__file__), spec_path]
    if spec["isolation"] == "netns":
        # Loopback up and multicast routed to it: LCM works inside, nothing leaves.
        driver = ["unshare", *_unshare_flags(), "sh", "-c",
                  'ip link set lo up && ip route add 224.0.0.0/4 dev lo && exec "$@"',
                  "game", *driver]
    # unshare and sh exec the driver in place: its parent is this thread. The
    # driver sets the parent-death signal again itself (the kernel clears it
    # when credentials change, as unshare -r's user namespace may make them)
    # and exits if this process is already gone.
    env = dict(os.environ, **{PARENT_ENV: str(os.getpid())})
    with open(os.path.join(game_dir, "driver.log"), "w") as log:
        process = subprocess.Popen(driver, stdout=log, stderr=subprocess.STDOUT, env=env,
                                   start_new_session=True, preexec_fn=die_with_parent)
        with _running_lock:
            _running[process.pid] = process
        try:
            process.wait()
        finally:
            with _running_lock:
                _running.pop(process.pid, None)
    result_path = os.path.join(game_dir, "result.json")
    if os.path.exists(result_path):
        with open(result_path) as f:
            return json.load(f)
    return failed(spec, f"driver exited with status {process.returncode} (see driver.log)")


def stop_all_games():
    """Ctrl-C: every driver's process group gets SIGTERM, then SIGKILL."""
    with _running_lock:
        processes = list(_running.values())
    for p in processes:
        try:
            os.killpg(p.pid, signal.SIGTERM)
        except ProcessLookupError:
            pass
    deadline = time.monotonic() + STOP_GRACE + 1.0
    for p in processes:
        try:
            p.wait(timeout=max(0.1, deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            try:
                os.killpg(p.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass


def failed(spec, reason):
    return {"index": spec["index"], "point": spec["point"], "seed": spec["seed"],
            "parameters": spec["parameters"], "status": "failed", "reason": reason,
            "log_dir": spec["game_dir"]}


def write_overlay(spec, config_dir):
    """The game's config folder: the shipped one, with each swept key replaced
    in a file that starts from the shipped file (BASE) and sets that key."""
    overlay = os.path.join(spec["game_dir"], "config")
    if os.path.exists(overlay):
        shutil.rmtree(overlay)
    os.makedirs(overlay)
    changed = {}
    for kind, name, key, value in spec["overrides"]:
        changed.setdefault((kind, name), []).append((key, value))
    kinds = {kind for kind, _ in changed}
    for entry in sorted(os.listdir(config_dir)):
        source = os.path.join(config_dir, entry)
        target = os.path.join(overlay, entry)
        if entry not in kinds:
            os.symlink(source, target)
            continue
        os.makedirs(target)
        for file_name in sorted(os.listdir(source)):
            os.symlink(os.path.join(source, file_name), os.path.join(target, file_name))
    for (kind, name), keys in changed.items():
        path = os.path.join(overlay, kind, name + ".cfg")
        os.remove(path)
        with open(path, "w") as f:
            f.write(f"# Written by ubersim_batch for game {spec['index']}: the shipped file with "
                    f"the swept keys set.\nBASE = {os.path.join(config_dir, kind, name + '.cfg')}\n")
            for key, value in keys:
                f.write(f"{key} = {value}\n")
    return overlay


def _team_command(spec, team, config_dir, lcm_url):
    template = spec["teams"][team]
    if template == "demo":
        template = DEMO
    sync = "--sync" if spec["mode"] == "sync" else ""
    text = template.format(bin=spec["bin_dir"], lcm_url=lcm_url, team=team,
                           config_dir=config_dir, sync=sync, seed=spec["seed"])
    return shlex.split(text)


# The protocol prefixes of a team program's command, as tools/launch.sh --team
# has them: none for the SSL simulation protocol. Here, not in experiment.py
# (which checks them too): game.py is the one file a distributed worker gets.
TEAM_PROTOCOLS = ("lcm", "grsim")


def team_protocol(command):
    """(protocol or None, the command without its prefix) of `team COMMAND`."""
    for protocol in TEAM_PROTOCOLS:
        if command.startswith(protocol + ":"):
            return protocol, command[len(protocol) + 1:]
    return None, command


def _bridge_command(spec, common, config_dir):
    """The SSL bridge that starts the team programs (team COMMAND) under the
    time shim, as tools/launch.sh --sync --team COLOUR 'COMMAND' has it do
    (docs/timeshim.md, "Integration with sync mode"). It logs at info level:
    each program's end and status are info lines (team_exits)."""
    bridge = [f"{spec['bin_dir']}/ubersim_ssl_bridge", *[c for c in common if c != "-q"],
              "--sync", "--tracked", "--listen-address", "127.0.0.1", "--local-only",
              "--team-output-dir", spec["game_dir"], "--seed", str(spec["seed"])]
    for colour, template in sorted(spec["team_programs"].items()):
        command = template.format(bin=spec["bin_dir"], team=colour, config_dir=config_dir,
                                  seed=spec["seed"])
        protocol, command = team_protocol(command)
        if protocol is not None:
            bridge += ["--team-protocol", colour, protocol]
        bridge += ["--team-command", colour, command]
    if spec.get("team_deterministic"):
        bridge.append("--team-deterministic")
    return bridge


# The bridge's line for the end of a team program (ssl_bridge/src/team_group.cpp).
TEAM_EXIT = re.compile(r"team (yellow|blue|both): the program exited with status (\d+) at sim "
                       r"time ([0-9.]+) s(, when the bridge stopped it)?")
# The time shim's findings (a thread blocked in a call it does not know, a busy
# thread, a program without the shim), as the bridge logs them.
TIMESHIM_PROBLEM = re.compile(r"\] timeshim: (?!every process of the team group has ended)")


def team_exits(bridge_log):
    """{colour: (status, sim time, ended on its own)} of the team programs that
    ended, from the bridge's log."""
    exits = {}
    if not os.path.exists(bridge_log):
        return exits
    with open(bridge_log, errors="replace") as f:
        for match in TEAM_EXIT.finditer(f.read()):
            exits[match.group(1)] = (int(match.group(2)), float(match.group(3)),
                                     match.group(4) is None)
    return exits


def early_team_exit(bridge_log, game_end=None):
    """The reason a game fails when a team program ended on its own before the
    game did (before game_end, s of sim time, when given): its team has no
    control from then on. None when none did."""
    for colour, (status, t, own) in sorted(team_exits(bridge_log).items()):
        if own and (game_end is None or t < game_end):
            return (f"{colour}'s team program exited with status {status} at sim time {t:.3f} s, "
                    f"before the game ended (see team_{colour}.log)")
    return None


def team_figures(game_dir, team_programs):
    """results.csv's columns of the team programs: each colour's exit status
    ("" for a team not started under the time shim) and the time shim's
    findings about them (timeshim_problems: lines in ssl_bridge.log)."""
    bridge_log = os.path.join(game_dir, "ssl_bridge.log")
    exits = team_exits(bridge_log)
    figures = {"yellow_team_status": "", "blue_team_status": "", "timeshim_problems": ""}
    for colour in team_programs:
        status = exits.get(colour, ("",))[0]
        for team in (("yellow", "blue") if colour == "both" else (colour,)):
            figures[f"{team}_team_status"] = status
    if team_programs and os.path.exists(bridge_log):
        with open(bridge_log, errors="replace") as f:
            figures["timeshim_problems"] = len(TIMESHIM_PROBLEM.findall(f.read()))
    return figures


class ProcessSet:
    """The game's processes; each logs to <game_dir>/<name>.log."""

    def __init__(self, game_dir):
        self.game_dir = game_dir
        self.processes = []  # (name, Popen)
        self.cpu = {}  # name -> CPU seconds (user + system) of the process, once reaped

    def start(self, name, command):
        log = open(os.path.join(self.game_dir, name + ".log"), "w")
        log.write("$ " + " ".join(shlex.quote(c) for c in command) + "\n")
        log.flush()
        # Dies with the driver even when the driver is SIGKILLed.
        p = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT,
                             stdin=subprocess.DEVNULL, preexec_fn=die_with_parent)
        log.close()
        self.processes.append((name, p))
        return p

    def _reap(self, name, p, block):
        """Reaps the process with wait4, which also gives its CPU time (Popen's
        own wait would reap it without): the benchmark's per-process figures."""
        if p.returncode is not None:
            return True
        try:
            pid, status, usage = os.wait4(p.pid, 0 if block else os.WNOHANG)
        except ChildProcessError:
            p.poll()  # already reaped elsewhere: no CPU figure
            return p.returncode is not None
        if pid == 0:
            return False
        p.returncode = os.waitstatus_to_exitcode(status)
        self.cpu[name] = round(usage.ru_utime + usage.ru_stime, 3)
        return True

    def first_exit(self):
        for name, p in self.processes:
            if self._reap(name, p, block=False):
                return name, p.returncode
        return None

    def stop(self):
        for name, p in self.processes:
            if not self._reap(name, p, block=False):
                p.terminate()
        deadline = time.monotonic() + STOP_GRACE
        for name, p in self.processes:
            while not self._reap(name, p, block=False) and time.monotonic() < deadline:
                time.sleep(0.02)
            if p.returncode is None:
                p.kill()
                self._reap(name, p, block=True)


def _wait_for_line(processes, name, text, timeout):
    """None once `name`'s log has `text`; the reason it failed otherwise."""
    path = os.path.join(processes.game_dir, name + ".log")
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        with open(path, errors="replace") as f:
            if text in f.read():
                return None
        exited = processes.first_exit()
        if exited is not None:
            return f"{exited[0]} exited with status {exited[1]} at the start (see {exited[0]}.log)"
        time.sleep(0.05)
    return f"{name} did not start within {timeout} s (see {name}.log)"


def read_events(path):
    """The event log: (events by type, fouls by team, result line or None)."""
    by_type, result = {}, None
    if not os.path.exists(path):
        return by_type, result
    with open(path) as f:
        for line in f:
            line = line.strip()
            if not line:
                continue
            record = json.loads(line)
            if "event" in record:
                by_type[record["event"]] = by_type.get(record["event"], 0) + 1
            elif "result" in record:
                result = record
    return by_type, result


# The radio emulator's lines for a dropped and a rejoined sync client
# (radio_emulator/src/sync_coordinator.cpp; docs/sync.md, "A dropped client").
SYNC_DROPPED = re.compile(r"sync client dropped: team (yellow|blue), client '([^']*)', "
                          r"at sim time ([0-9.]+) s")
SYNC_REJOINED = re.compile(r"sync client rejoined: team (yellow|blue), client '[^']*', "
                           r"at sim time ([0-9.]+) s")


def control_losses(radio_log, end):
    """{team: {"drops", "without_control", "client", "first_drop"}} for each team
    whose sync client the radio emulator dropped before `end` (s of sim time):
    without control from each drop until it rejoined, or until `end`."""
    losses = {}
    dropped_at = {}
    if not os.path.exists(radio_log):
        return losses
    with open(radio_log, errors="replace") as f:
        for line in f:
            drop = SYNC_DROPPED.search(line)
            if drop and float(drop.group(3)) < end:
                team, t = drop.group(1), float(drop.group(3))
                loss = losses.setdefault(team, {"drops": 0, "without_control": 0.0,
                                                "client": drop.group(2), "first_drop": t})
                loss["drops"] += 1
                dropped_at[team] = t
                continue
            rejoin = SYNC_REJOINED.search(line)
            if rejoin and rejoin.group(1) in dropped_at:
                team = rejoin.group(1)
                since = dropped_at.pop(team)
                losses[team]["without_control"] += min(float(rejoin.group(2)), end) - since
    for team, since in dropped_at.items():
        losses[team]["without_control"] += end - since
    for loss in losses.values():
        loss["without_control"] = round(loss["without_control"], 3)
    return losses


def degraded_reason(losses, end):
    """The reason column of a game whose teams lost control."""
    parts = []
    for team in sorted(losses):
        loss = losses[team]
        times = "time" if loss["drops"] == 1 else "times"
        parts.append(f"{team}'s sync client '{loss['client']}' was dropped {loss['drops']} {times} "
                     f"(first at {loss['first_drop']:.3f} s): {team} without control for "
                     f"{loss['without_control']:.3f} s of {end:.3f} s of sim time")
    return "; ".join(parts) + " (see radio.log)"


def _referee_command(spec, lcm_url, config_dir, events_path):
    """The referee's command line, and the line its log has once it listens:
    the built-in automatic referee, or the link to the official game
    controller (REFEREE = official PATH, sync mode only), which starts the GC
    in CI mode with its folder in the game's (gc/)."""
    bin_dir = spec["bin_dir"]
    # The referee logs its game at info level (its log is the game's story).
    common = ["--lcm-url", lcm_url, "--config-dir", config_dir, "--timeout", "20"]
    game = ["--game", spec["game"], "--game-length", str(spec["game_length"]),
            "--events", events_path]
    if spec.get("referee") == "official":
        return ([f"{bin_dir}/ubersim_gc_link", *common, *game,
                 "--game-controller", spec["game_controller"],
                 "--gc-dir", os.path.join(spec["game_dir"], "gc")],
                "official game controller on")
    referee = [f"{bin_dir}/ubersim_referee", *common, "auto", *game]
    referee += ["--sync"] if spec["mode"] == "sync" else ["--start"]
    if spec.get("judging") == "every_step":
        referee += ["--judge-every-step"]
    return referee, "automatic referee:"


def outcome(result_line):
    """The game's figures from the referee's result line. The built-in referee
    keeps shots and possession and gives no cards; the official game
    controller gives cards and keeps neither: what a referee does not keep is
    "" (empty in results.csv, left out of the summary)."""
    y, b = result_line["yellow"], result_line["blue"]
    figures = {"yellow_goals": y["goals"], "blue_goals": b["goals"],
               "score_difference": y["goals"] - b["goals"],
               "yellow_fouls": y["fouls"], "blue_fouls": b["fouls"]}
    for team, t in (("yellow", y), ("blue", b)):
        figures[f"{team}_shots"] = t.get("shots", "")
        figures[f"{team}_yellow_cards"] = t.get("yellow_cards", "")
        figures[f"{team}_red_cards"] = t.get("red_cards", "")
    played = y.get("possession", 0) + b.get("possession", 0)
    if "possession" not in y:
        figures["yellow_possession"] = figures["blue_possession"] = ""
    else:
        figures["yellow_possession"] = round(y["possession"] / played, 4) if played > 0 else 0.5
        figures["blue_possession"] = round(b["possession"] / played, 4) if played > 0 else 0.5
    return figures


def vision_frames_lost(log_path):
    """The vision emulator's "frames lost" from its exit summary. It runs with
    -q, and logs that summary (at warning level) only when it lost a frame:
    no summary in its log is 0."""
    if not os.path.exists(log_path):
        return ""
    with open(log_path) as f:
        found = re.findall(r"summary: frames lost (\d+)", f.read())
    return int(found[-1]) if found else 0


def run_driver(spec):
    """Runs the game in this process's network (namespace); writes result.json."""
    game_dir = spec["game_dir"]
    config_dir = write_overlay(spec, spec["config_dir"])
    lcm_url = f"udpm://239.255.76.67:{spec['port']}?ttl=0&recv_buf_size=4194304"
    common = ["--lcm-url", lcm_url, "--config-dir", config_dir, "-q"]
    bin_dir = spec["bin_dir"]
    seed = str(spec["seed"])
    sync = spec["mode"] == "sync"
    events_path = os.path.join(game_dir, "events.jsonl")
    processes = ProcessSet(game_dir)
    stop = {"signal": None}

    def on_signal(number, _frame):
        stop["signal"] = number

    signal.signal(signal.SIGTERM, on_signal)
    signal.signal(signal.SIGINT, on_signal)

    # Fast mode: physics starts paused and the referee resumes it once every
    # process listens. Sync mode: physics holds at sim time 0 until both teams
    # registered, and then steps only past states the referee has judged
    # (--sync-referee), so the referee is started, and listening, first.
    physics = [f"{bin_dir}/ubersim_physics", *common, "--scenario", spec["scenario"],
               "--seed", seed, "--duration", str(2 * spec["game_length"] + 120)]
    # Sync mode: physics waits for the referee only at the states it judges,
    # and (ground truth on demand, the default) sends only those and the
    # emulators' (docs/sync.md, docs/autoref.md "Judging rate").
    physics += ["--sync-referee"] if sync else ["--speed", "0", "--paused"]
    radio = [f"{bin_dir}/ubersim_radio", *common, "--profile", spec["radio_profile"],
             "--seed", seed]
    if sync:
        radio += ["--sync", "--sync-clients", "2"]
    if spec.get("team_programs"):
        # As tools/launch.sh --team: the time shim names a stuck team thread;
        # the radio drops only a team that computes this long at one instant.
        radio += ["--sync-timeout", "30"]
    referee, referee_ready = _referee_command(spec, lcm_url, config_dir, events_path)
    wall_start = time.monotonic()
    next_team_look = wall_start
    reason = None
    try:
        processes.start("physics", physics)
        processes.start("vision", [f"{bin_dir}/ubersim_vision", *common,
                                   "--profile", spec["vision_profile"], "--seed", seed])
        processes.start("radio", radio)
        if sync:
            processes.start("referee", referee)
            reason = _wait_for_line(processes, "referee", referee_ready, 30)
        if reason is None:
            for team in sorted(spec["teams"]):
                processes.start(team, _team_command(spec, team, config_dir, lcm_url))
            if spec.get("team_programs"):
                processes.start("ssl_bridge", _bridge_command(spec, common, config_dir))
        if reason is None and not sync:
            time.sleep(0.5)  # every listener subscribed before the game starts
            processes.start("referee", referee)
        while reason is None:
            if stop["signal"] is not None:
                reason = "stopped by a signal"
                break
            exited = processes.first_exit()
            if exited is not None:
                name, status = exited
                if name != "referee" or status != 0:
                    reason = (f"{name} exited with status {status} before the game ended "
                              f"(see {name}.log)")
                break
            if spec.get("team_programs") and time.monotonic() >= next_team_look:
                next_team_look = time.monotonic() + 0.5
                reason = early_team_exit(os.path.join(game_dir, "ssl_bridge.log"))
                if reason is not None:
                    break
            if time.monotonic() - wall_start > spec["timeout"]:
                reason = f"no result within GAME_TIMEOUT = {spec['timeout']} s of wall time"
                break
            time.sleep(0.05)
    finally:
        processes.stop()
    wall = time.monotonic() - wall_start
    by_type, result_line = read_events(events_path)
    if reason is None and (result_line is None or not result_line.get("game_over")):
        reason = "the referee ended without a finished game (see referee.log)"
    if reason is None and spec.get("team_programs"):
        reason = early_team_exit(os.path.join(game_dir, "ssl_bridge.log"), result_line["t"])
    if reason is not None:
        result = failed(spec, reason)
        if spec.get("team_programs"):
            result.update(team_figures(game_dir, spec["team_programs"]))
    else:
        sim_time = result_line["t"]
        # A team whose client was dropped played part of the game without
        # control: the score is not that of a fair game.
        losses = control_losses(os.path.join(game_dir, "radio.log"), sim_time)
        result = {
            "index": spec["index"], "point": spec["point"], "seed": spec["seed"],
            "parameters": spec["parameters"], "status": "degraded" if losses else "ok",
            "reason": degraded_reason(losses, sim_time) if losses else "",
            **outcome(result_line),
            "events": sum(by_type.values()),
            "events_by_type": by_type,
            "sim_time": sim_time,
            "wall_time": round(wall, 3),
            "speed": round(sim_time / wall, 3) if wall > 0 else 0.0,
            "yellow_without_control": losses.get("yellow", {}).get("without_control", 0.0),
            "blue_without_control": losses.get("blue", {}).get("without_control", 0.0),
            # As fast as possible physics waits for the vision, so this is 0
            # unless something went wrong; never lost silently (docs/vision.md).
            "vision_frames_lost": vision_frames_lost(os.path.join(game_dir, "vision.log")),
            **team_figures(game_dir, spec.get("team_programs", {})),
            "cpu": processes.cpu,
            "log_dir": game_dir,
        }
    with open(os.path.join(game_dir, "result.json"), "w") as f:
        json.dump(result, f, indent=1)
    return result


if __name__ == "__main__":
    # The driver dies with the process that started it (a Dask worker, the runner).
    die_with_parent()
    if PARENT_ENV in os.environ and os.getppid() != int(os.environ[PARENT_ENV]):
        sys.exit("game driver: the process that started it is gone")
    with open(sys.argv[1]) as spec_file:
        run_driver(json.load(spec_file))
