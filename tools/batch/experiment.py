"""An experiment file (config/experiments/*.cfg) and the games it asks for.

The file is in ubersim's config format and is read by the same parser as every
other config file (ubersim_config_check --dump), so syntax errors, BASE chains
and quoting behave the same; every error here names the file and the line.
"""
import itertools
import json
import os
import subprocess

# game.py is the one file a distributed worker gets: what both need lives there.
from game import team_protocol

# Keys of an experiment file: (required, what the value is).
KEYS = {
    "SCENARIO": "scenario name (config/scenarios)",
    "VISION_PROFILE": "vision profile name (config/vision)",
    "RADIO_PROFILE": "radio profile name (config/radio)",
    "GAME": "referee game config (config/referee)",
    "GAME_LENGTH": "s of sim time per game",
    "GAMES_PER_POINT": "games at each sweep point",
    "SEED": "seed of the first game of each point; game k runs with SEED + k",
    "YELLOW": "demo, the yellow team's command line (a sync client of its own), or team COMMAND "
              "(any program, started under the time shim: tools/launch.sh --team)",
    "BLUE": "demo, the blue team's command line, or team COMMAND",
    "BOTH": "team COMMAND: one program under the time shim plays both colours (then no YELLOW "
            "and BLUE)",
    "TEAM_DETERMINISTIC": "no (default) or yes: the team programs' threads run one at a time "
                          "in a fixed order (tools/launch.sh --team-deterministic)",
    "MODE": "sync (reproducible, as fast as the teams answer) or fast (as fast as possible)",
    "GAME_TIMEOUT": "s of wall time after which a game counts as failed",
    "JUDGING": "adaptive (the referee judges the states where a rule could decide) or "
               "every_step (every state: slower, the same decisions)",
    "REFEREE": "builtin (ubersim's automatic referee) or official PATH (the official "
               "ssl-game-controller at PATH, in its CI mode; MODE = sync)",
}
OPTIONAL = {"SWEEP", "GAME_TIMEOUT", "MODE", "JUDGING", "REFEREE", "BOTH", "TEAM_DETERMINISTIC"}
DEFAULTS = {"GAME_TIMEOUT": ["900"], "MODE": ["sync"], "JUDGING": ["adaptive"],
            "REFEREE": ["builtin"], "TEAM_DETERMINISTIC": ["no"]}
# What a team program's command line (team COMMAND) may name: it gets its bus
# and its clock from the SSL bridge, so not {lcm_url} nor {sync}.
TEAM_PLACEHOLDERS = {"bin": "", "team": "", "config_dir": "", "seed": 0}

# Short names of the files a sweep key may change: kind folder, experiment key
# naming the file.
SHORT_KINDS = {
    "vision": ("vision", "VISION_PROFILE"),
    "radio": ("radio", "RADIO_PROFILE"),
    "game": ("referee", "GAME"),
    "physics": ("physics", None),
}


class ExperimentError(Exception):
    """A problem in the experiment file; the message starts with file:line."""


def config_dump(bin_dir, path):
    """Every key of a config file: {KEY: {"where": "file:line", "values": [...]}}."""
    tool = os.path.join(bin_dir, "ubersim_config_check")
    if not os.access(tool, os.X_OK):
        raise ExperimentError(f"{tool} not found: run tools/build.sh")
    run = subprocess.run([tool, "any", path, "--dump"], capture_output=True, text=True)
    if run.returncode != 0:
        raise ExperimentError(run.stderr.strip() or f"{path}: cannot be read")
    return json.loads(run.stdout)


def _number(entry, key, kind=float, minimum=None):
    values = entry["values"]
    if len(values) != 1:
        raise ExperimentError(f"{entry['where']}: {key}: expected one value, got {len(values)}")
    try:
        value = kind(values[0])
    except ValueError:
        raise ExperimentError(
            f"{entry['where']}: {key}: expected {'an integer' if kind is int else 'a number'}, "
            f"got '{values[0]}'") from None
    if minimum is not None and value < minimum:
        raise ExperimentError(f"{entry['where']}: {key}: expected at least {minimum}, got {value}")
    return value


def _sweep_values(entry, key, tokens):
    """'0.035 0.05 0.1' or '0.035..0.1:4' (4 points, ends included)."""
    if len(tokens) == 1 and ".." in tokens[0]:
        try:
            span, _, count = tokens[0].partition(":")
            low, high = (float(t) for t in span.split(".."))
            n = int(count) if count else 2
        except ValueError:
            raise ExperimentError(
                f"{entry['where']}: {key}: expected FROM..TO:POINTS, got '{tokens[0]}'") from None
        if n < 2:
            raise ExperimentError(f"{entry['where']}: {key}: a range needs at least 2 points")
        return [repr(round(low + (high - low) * i / (n - 1), 12)) for i in range(n)]
    return list(tokens)


class Sweep:
    """One swept key: which config file it changes, and its values."""

    def __init__(self, name, kind, file_name, key, values, where):
        self.name = name          # as written: vision.LATENCY, robots/omni4_ssl.MAX_SPEED
        self.kind = kind          # config folder: vision, radio, robots, referee, ...
        self.file_name = file_name
        self.key = key
        self.values = values
        self.where = where


class Experiment:
    def __init__(self, path, bin_dir, config_dir):
        self.path = path
        entries = config_dump(bin_dir, path)
        for key, entry in entries.items():
            if key not in KEYS and not key.startswith("SWEEP"):
                raise ExperimentError(
                    f"{entry['where']}: unknown key '{key}': expected one of "
                    f"{', '.join(sorted(KEYS))} or SWEEP, SWEEP_<n>")
        for key in KEYS:
            if key not in entries and key not in OPTIONAL and not (
                    key in ("YELLOW", "BLUE") and "BOTH" in entries):
                raise ExperimentError(f"{path}: missing key {key} ({KEYS[key]})")
        for key, value in DEFAULTS.items():
            entries.setdefault(key, {"where": path, "values": value})

        def one(key):
            entry = entries[key]
            if len(entry["values"]) != 1:
                raise ExperimentError(f"{entry['where']}: {key}: expected one value")
            return entry["values"][0]

        self.scenario = one("SCENARIO")
        self.vision_profile = one("VISION_PROFILE")
        self.radio_profile = one("RADIO_PROFILE")
        self.game = one("GAME")
        self.game_length = _number(entries["GAME_LENGTH"], "GAME_LENGTH", float, 0.1)
        self.games_per_point = _number(entries["GAMES_PER_POINT"], "GAMES_PER_POINT", int, 1)
        self.seed = _number(entries["SEED"], "SEED", int, 0)
        self.game_timeout = _number(entries["GAME_TIMEOUT"], "GAME_TIMEOUT", float, 1)
        self.mode = one("MODE")
        if self.mode not in ("sync", "fast"):
            raise ExperimentError(f"{entries['MODE']['where']}: MODE: expected sync or fast, "
                                  f"got '{self.mode}'")
        self.judging = one("JUDGING")
        if self.judging not in ("adaptive", "every_step"):
            raise ExperimentError(f"{entries['JUDGING']['where']}: JUDGING: expected adaptive or "
                                  f"every_step, got '{self.judging}'")
        self.referee, self.game_controller = self._referee(entries["REFEREE"])
        self.teams, self.team_programs = {}, {}
        self._teams(entries)
        names = {"SCENARIO": ("scenarios", self.scenario),
                 "VISION_PROFILE": ("vision", self.vision_profile),
                 "RADIO_PROFILE": ("radio", self.radio_profile),
                 "GAME": ("referee", self.game)}
        for key, (kind, name) in names.items():
            if not os.path.exists(os.path.join(config_dir, kind, name + ".cfg")):
                raise ExperimentError(f"{entries[key]['where']}: {key}: no file "
                                      f"{kind}/{name}.cfg in the config folder")
        self.sweeps = []
        for key in sorted(k for k in entries if k.startswith("SWEEP")):
            self.sweeps.append(self._sweep(entries, key, bin_dir, config_dir))

    def _teams(self, entries):
        """self.teams: {colour: "demo" or a command line} of the teams started
        as they are; self.team_programs: {colour or "both": command} of those
        the SSL bridge starts under the time shim (team COMMAND; "lcm:COMMAND"
        speaks LCM, "grsim:COMMAND" grSim's protocol, as in tools/launch.sh --team)."""
        if "BOTH" in entries:
            for key in ("YELLOW", "BLUE"):
                if key in entries:
                    raise ExperimentError(
                        f"{entries[key]['where']}: {key}: BOTH (line "
                        f"{entries['BOTH']['where'].rpartition(':')[2]}) names one program for "
                        f"both colours: leave out YELLOW and BLUE")
            command = self._team_program(entries["BOTH"], "BOTH", required=True)
            if team_protocol(command)[0] == "lcm":
                raise ExperimentError(f"{entries['BOTH']['where']}: BOTH: an LCM program plays "
                                      f"one colour (YELLOW = team lcm:COMMAND)")
            self.team_programs["both"] = command
        for key in ("YELLOW", "BLUE"):
            if key not in entries:
                continue
            command = self._team_program(entries[key], key)
            if command is None:
                self.teams[key.lower()] = " ".join(entries[key]["values"])
            else:
                self.team_programs[key.lower()] = command
        entry = entries["TEAM_DETERMINISTIC"]
        if entry["values"] not in (["yes"], ["no"]):
            raise ExperimentError(f"{entry['where']}: TEAM_DETERMINISTIC: expected yes or no, "
                                  f"got '{' '.join(entry['values'])}'")
        self.team_deterministic = entry["values"] == ["yes"]
        if self.team_deterministic and not self.team_programs:
            raise ExperimentError(f"{entry['where']}: TEAM_DETERMINISTIC: only with a team "
                                  f"program (YELLOW, BLUE or BOTH = team COMMAND)")

    def _team_program(self, entry, key, required=False):
        """The command of `team COMMAND`, checked; None for another value."""
        values, where = entry["values"], entry["where"]
        if values[0] != "team":
            if required:
                raise ExperimentError(f"{where}: {key}: expected team COMMAND, got "
                                      f"'{' '.join(values)}'")
            return None
        command = " ".join(values[1:]).strip()
        if not team_protocol(command)[1].strip():
            raise ExperimentError(f"{where}: {key}: expected team COMMAND (the program's "
                                  f"command line after 'team'), got nothing")
        if self.mode != "sync":
            raise ExperimentError(f"{where}: {key}: a team program runs under the time shim, "
                                  f"on the simulation's clock: MODE must be sync")
        try:
            command.format(**TEAM_PLACEHOLDERS)
        except (KeyError, IndexError) as error:
            raise ExperimentError(
                f"{where}: {key}: {{{error.args[0]}}}: expected only {{bin}}, {{team}}, "
                f"{{config_dir}} or {{seed}} in a team program's command line (it gets its "
                f"bus and clock from the SSL bridge)") from None
        except ValueError as error:  # a lone brace
            raise ExperimentError(f"{where}: {key}: {error} (write {{{{ and }}}} for a "
                                  f"brace)") from None
        return command

    def _referee(self, entry):
        """("builtin", None) or ("official", absolute path of the game controller)."""
        values, where = entry["values"], entry["where"]
        if values == ["builtin"]:
            return "builtin", None
        if len(values) != 2 or values[0] != "official":
            raise ExperimentError(f"{where}: REFEREE: expected builtin or official PATH (the "
                                  f"ssl-game-controller binary), got '{' '.join(values)}'")
        path = os.path.join(os.path.dirname(os.path.abspath(self.path)),
                            os.path.expanduser(values[1]))
        if not (os.path.isfile(path) and os.access(path, os.X_OK)):
            raise ExperimentError(f"{where}: REFEREE: '{values[1]}' is not an executable file "
                                  f"(the ssl-game-controller binary)")
        if self.mode != "sync":
            raise ExperimentError(f"{where}: REFEREE: the official game controller referees in "
                                  f"its CI mode, sim time its clock: MODE must be sync")
        if self.judging != "adaptive":
            raise ExperimentError(f"{where}: REFEREE: JUDGING = every_step is the built-in "
                                  f"referee's; with the official game controller leave it out")
        return "official", os.path.normpath(path)

    def _sweep(self, entries, key, bin_dir, config_dir):
        entry = entries[key]
        tokens = entry["values"]
        if len(tokens) < 2:
            raise ExperimentError(f"{entry['where']}: {key}: expected a key and its values, e.g. "
                                  f"'vision.LATENCY 0.035 0.1'")
        name = tokens[0]
        target, dot, config_key = name.rpartition(".")
        if not dot or not target or not config_key:
            raise ExperimentError(f"{entry['where']}: {key}: '{name}': expected FILE.KEY, e.g. "
                                  f"vision.LATENCY or robots/omni4_ssl.MAX_SPEED")
        if target in SHORT_KINDS:
            kind, name_key = SHORT_KINDS[target]
            file_name = one_value(entries, name_key) if name_key else "default"
        elif "/" in target:
            kind, _, file_name = target.partition("/")
        else:
            raise ExperimentError(f"{entry['where']}: {key}: '{target}': expected vision, radio, "
                                  f"game, physics or KIND/NAME (e.g. robots/omni4_ssl)")
        path = os.path.join(config_dir, kind, file_name + ".cfg")
        if not os.path.exists(path):
            raise ExperimentError(f"{entry['where']}: {key}: no config file {kind}/{file_name}.cfg")
        if config_key not in config_dump(bin_dir, path):
            raise ExperimentError(f"{entry['where']}: {key}: {kind}/{file_name}.cfg has no key "
                                  f"{config_key}")
        values = _sweep_values(entry, key, tokens[1:])
        return Sweep(name, kind, file_name, config_key, values, entry["where"])

    def points(self):
        """Every combination of the sweeps' values, as [(Sweep, value), ...]."""
        if not self.sweeps:
            return [[]]
        return [list(zip(self.sweeps, combo))
                for combo in itertools.product(*(s.values for s in self.sweeps))]

    def games(self):
        """One spec (a plain dict, JSON-able) per game, in a fixed order."""
        specs = []
        for point_index, point in enumerate(self.points()):
            for k in range(self.games_per_point):
                specs.append({
                    "index": len(specs),
                    "point": point_index,
                    "seed": self.seed + k,
                    "parameters": {s.name: v for s, v in point},
                    "overrides": [[s.kind, s.file_name, s.key, v] for s, v in point],
                    "scenario": self.scenario,
                    "vision_profile": self.vision_profile,
                    "radio_profile": self.radio_profile,
                    "game": self.game,
                    "game_length": self.game_length,
                    "mode": self.mode,
                    "judging": self.judging,
                    "referee": self.referee,
                    "game_controller": self.game_controller,
                    "teams": self.teams,
                    "team_programs": self.team_programs,
                    "team_deterministic": self.team_deterministic,
                    "timeout": self.game_timeout,
                })
        return specs


def one_value(entries, key):
    entry = entries[key]
    return entry["values"][0]
