#!/usr/bin/python3
"""The batch runner with real processes: the shipped smoke experiment, errors
that name file and line, a crashing team program, Ctrl-C. Each test works in a
temporary folder of its own and removes it when it passes.

Usage: test_batch.py SOURCE_DIR BUILD_DIR [unittest arguments]
"""
import csv
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest

SOURCE, BUILD = sys.argv[1], sys.argv[2]
BATCH = os.path.join(SOURCE, "tools", "ubersim_batch")
SMOKE = os.path.join(SOURCE, "config", "experiments", "smoke.cfg")
sys.path.insert(0, os.path.join(SOURCE, "tools", "batch"))
import results as results_module  # noqa: E402
from live_processes import processes_mentioning  # noqa: E402


def run_batch(*args, timeout=600):
    return subprocess.run([BATCH, "run", *args, "--build-dir", BUILD, "-q"],
                          capture_output=True, text=True, timeout=timeout)


def rows(out_dir):
    with open(os.path.join(out_dir, "results.csv")) as f:
        return list(csv.DictReader(f))


def experiment(folder, text, name="experiment.cfg"):
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        f.write(text)
    return path


SHORT = """SCENARIO = division_b_6v6
VISION_PROFILE = cmdragons02
RADIO_PROFILE = cmdragons02
GAME = division_b
GAME_LENGTH = 4
GAMES_PER_POINT = 2
SEED = 1
YELLOW = demo
BLUE = demo
MODE = fast
GAME_TIMEOUT = 60
"""


# The CI-mode stand-in for the official game controller as a program (CI
# machines cannot build the GC; tests/gc_link/standin_main.cpp), and the real
# GC when UBERSIM_SSL_GC names it.
STANDIN_GC = os.path.abspath(os.path.join(BUILD, "bin", "ubersim_standin_gc"))
REAL_GC = os.environ.get("UBERSIM_SSL_GC", "")
OFFICIAL = """SCENARIO = division_b_6v6
VISION_PROFILE = cmdragons02
RADIO_PROFILE = cmdragons02
GAME = division_b
GAME_LENGTH = {length}
GAMES_PER_POINT = 2
SEED = {seed}
YELLOW = demo
BLUE = demo
REFEREE = official {gc}
GAME_TIMEOUT = 120
"""


# Team programs started by the batch under the time shim (team COMMAND,
# docs/batch.md): the C++ SSL test team (tests/ssl_bridge/ssl_timed_team: a
# receiver thread, a 50 Hz loop, wall-clock reads) as yellow, the demo team
# without --sync on LCM as blue. The same point twice: two games, same seed.
TIMED_TEAM = os.path.join(BUILD, "bin", "ssl_timed_team")
TEAM_PROGRAMS = """SCENARIO = division_b_6v6
VISION_PROFILE = cmdragons02
RADIO_PROFILE = cmdragons02
GAME = division_b
GAME_LENGTH = 4
GAMES_PER_POINT = 1
SEED = 5
YELLOW = team "{bin}/ssl_timed_team --team {team}"
BLUE = team "lcm:{bin}/ubersim_demo_team --team {team} --config-dir {config_dir}"
SWEEP = vision.LATENCY 0.035 0.035
GAME_TIMEOUT = 60
"""


def event_log_counts(game_dir):
    """Game events by type, and the result line, of a game's event log."""
    counts, result = {}, None
    with open(os.path.join(game_dir, "events.jsonl")) as f:
        for line in f:
            record = json.loads(line)
            if "event" in record:
                counts[record["event"]] = counts.get(record["event"], 0) + 1
            elif "result" in record:
                result = record
    return counts, result


def ubersim_processes_under(folder):
    """Processes whose command line mentions `folder` (the games' config and logs)."""
    return [f"{pid}: {command}" for pid, command in processes_mentioning(folder).items()]


class BatchTest(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.mkdtemp(prefix="ubersim-batch-test-")

    def run(self, result=None):
        # The temporary folder goes when the test passed, stays (and is named) when not.
        result = result or self.defaultTestResult()
        failures = len(result.failures) + len(result.errors)
        super().run(result)
        if not hasattr(self, "folder"):  # skipped: setUp did not run
            return result
        if len(result.failures) + len(result.errors) == failures:
            shutil.rmtree(self.folder, ignore_errors=True)
        else:
            print(f"kept {self.folder} for inspection", file=sys.stderr)
        return result

    def test_smoke_experiment_runs_four_games_and_writes_results_summary_figure(self):
        out = os.path.join(self.folder, "smoke")
        run = run_batch(SMOKE, "--out", out)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        games = rows(out)
        self.assertEqual(len(games), 4)
        self.assertEqual(sorted({g["vision.LATENCY"] for g in games}), ["0.035", "0.1"])
        self.assertEqual([g["seed"] for g in games], ["1", "2", "1", "2"])
        for g in games:
            self.assertEqual(g["status"], "ok", g)
            # 30 s of game time plus the stops, kick-offs and the half-time break.
            self.assertGreater(float(g["sim_time"]), 30.0)
            self.assertLess(float(g["sim_time"]), 60.0)
            self.assertEqual(int(g["score_difference"]),
                             int(g["yellow_goals"]) - int(g["blue_goals"]))
            self.assertAlmostEqual(
                float(g["yellow_possession"]) + float(g["blue_possession"]), 1.0, places=3)
            self.assertGreater(float(g["speed"]), 0.0)
            self.assertEqual(g["vision_frames_lost"], "0")
            # What each process of the game cost: the benchmark's per-process figures.
            cpu = results_module.cpu_by_process(g)
            self.assertEqual(sorted(cpu), ["blue", "physics", "radio", "referee", "vision",
                                           "yellow"], g["cpu_seconds"])
            self.assertGreater(cpu["physics"], 0.0)
            # Each game kept its own event log and the logs of its processes.
            for log in ("events.jsonl", "physics.log", "referee.log", "yellow.log"):
                self.assertTrue(os.path.exists(os.path.join(g["log_dir"], log)), log)
        with open(os.path.join(out, "summary.csv")) as f:
            summary = list(csv.DictReader(f))
        self.assertEqual(len(summary), 2)
        self.assertEqual([s["games"] for s in summary], ["2", "2"])
        self.assertIn("score_difference_ci95", summary[0])
        if shutil.which("gnuplot"):
            self.assertTrue(os.path.exists(os.path.join(out, "score_difference_0.png")))
        self.assertIn("game seconds per wall second", run.stdout)

    def test_errors_in_the_experiment_file_name_file_and_line(self):
        cases = [
            (SHORT + "GAMES_PER_PONT = 3\n", "experiment.cfg:12: unknown key 'GAMES_PER_PONT'"),
            (SHORT + "SWEEP = vision.LATENCYY 0.1 0.2\n",
             "experiment.cfg:12: SWEEP: vision/cmdragons02.cfg has no key LATENCYY"),
            (SHORT.replace("GAME_LENGTH = 4", "GAME_LENGTH = four"),
             "experiment.cfg:5: GAME_LENGTH: expected a number, got 'four'"),
            (SHORT + "SWEEP = vision.LATENCY 0.1..0.2:x\n",
             "experiment.cfg:12: SWEEP: expected FROM..TO:POINTS"),
            (SHORT.replace("SCENARIO = division_b_6v6\n", ""), "missing key SCENARIO"),
            (SHORT + "JUDGING = sometimes\n",
             "experiment.cfg:12: JUDGING: expected adaptive or every_step, got 'sometimes'"),
            (SHORT + "REFEREE = autoref\n",
             "experiment.cfg:12: REFEREE: expected builtin or official PATH"),
            (SHORT + "REFEREE = official no-such-gc\n",
             "experiment.cfg:12: REFEREE: 'no-such-gc' is not an executable file"),
            (SHORT + f"REFEREE = official {STANDIN_GC}\n",  # SHORT is MODE = fast
             "experiment.cfg:12: REFEREE: the official game controller referees in its CI mode"),
            # Team programs under the time shim (team COMMAND).
            (SHORT.replace("YELLOW = demo", "YELLOW = team"),
             "experiment.cfg:8: YELLOW: expected team COMMAND (the program's command line"),
            (SHORT.replace("YELLOW = demo", "YELLOW = team grsim:"),
             "experiment.cfg:8: YELLOW: expected team COMMAND (the program's command line"),
            (SHORT.replace("YELLOW = demo", "YELLOW = team prog"),
             "experiment.cfg:8: YELLOW: a team program runs under the time shim, on the "
             "simulation's clock: MODE must be sync"),
            (SHORT.replace("MODE = fast", "MODE = sync").replace(
                "BLUE = demo", "BLUE = team 'prog --lcm-url {lcm_url}'"),
             "experiment.cfg:9: BLUE: {lcm_url}: expected only {bin}, {team}, {config_dir} or "
             "{seed}"),
            (SHORT.replace("MODE = fast", "MODE = sync") + "BOTH = team prog\n",
             "experiment.cfg:8: YELLOW: BOTH (line 12) names one program for both "
             "colours: leave out YELLOW and BLUE"),
            (SHORT.replace("MODE = fast", "MODE = sync").replace("YELLOW = demo\nBLUE = demo\n", "")
             + "BOTH = team lcm:prog\n",
             "experiment.cfg:10: BOTH: an LCM program plays one colour"),
            (SHORT.replace("MODE = fast", "MODE = sync").replace("YELLOW = demo\nBLUE = demo\n", "")
             + "BOTH = prog\n", "experiment.cfg:10: BOTH: expected team COMMAND, got 'prog'"),
            (SHORT + "TEAM_DETERMINISTIC = yes\n",
             "experiment.cfg:12: TEAM_DETERMINISTIC: only with a team program"),
            (SHORT + "TEAM_DETERMINISTIC = maybe\n",
             "experiment.cfg:12: TEAM_DETERMINISTIC: expected yes or no, got 'maybe'"),
        ]
        for text, message in cases:
            path = experiment(self.folder, text)
            run = run_batch(path, "--out", os.path.join(self.folder, "out"))
            self.assertEqual(run.returncode, 2, run.stderr)
            self.assertIn(message, run.stderr)

    def official_games(self, gc, length, seed):
        """A batch of two games under the official game controller `gc`: the
        rows take score, cards and game events from the GC's messages (the
        link's event log); shots and possession, which the GC does not keep,
        are empty."""
        path = experiment(self.folder, OFFICIAL.format(gc=gc, length=length, seed=seed))
        out = os.path.join(self.folder, "official")
        run = run_batch(path, "--out", out)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        self.assertIn("the official game controller", run.stdout)
        games = rows(out)
        self.assertEqual(len(games), 2)
        for g in games:
            self.assertEqual(g["status"], "ok", g)
            counts, result = event_log_counts(g["log_dir"])
            self.assertTrue(result["game_over"], result)
            for team in ("yellow", "blue"):
                self.assertEqual(int(g[f"{team}_goals"]), result[team]["goals"])
                self.assertEqual(int(g[f"{team}_fouls"]), result[team]["fouls"])
                self.assertEqual(int(g[f"{team}_yellow_cards"]), result[team]["yellow_cards"])
                self.assertEqual(int(g[f"{team}_red_cards"]), result[team]["red_cards"])
                self.assertEqual(g[f"{team}_shots"], "")
                self.assertEqual(g[f"{team}_possession"], "")
            self.assertEqual(g["event_types"],
                             " ".join(f"{k}:{counts[k]}" for k in sorted(counts)))
            self.assertGreater(float(g["sim_time"]), length)
            self.assertTrue(os.path.isdir(os.path.join(g["log_dir"], "gc")), g["log_dir"])
        self.assertTrue(any(g["event_types"] for g in games), games)
        return games

    @unittest.skipUnless(os.access(STANDIN_GC, os.X_OK), "ubersim_standin_gc is not built")
    def test_official_referee_takes_the_result_from_the_game_controller(self):
        self.official_games(STANDIN_GC, 6, 4)

    @unittest.skipUnless(REAL_GC, "UBERSIM_SSL_GC does not name the ssl-game-controller binary")
    def test_official_referee_with_the_real_game_controller(self):
        games = self.official_games(REAL_GC, 24, 3)
        # Seed 3: the demo teams score once, and the GC decides it is a goal.
        self.assertEqual(games[0]["yellow_goals"], "1")
        self.assertIn("GOAL:1", games[0]["event_types"])

    @unittest.skipUnless(os.access(TIMED_TEAM, os.X_OK) and os.access(
        os.path.join(BUILD, "bin", "ubersim_ssl_bridge"), os.X_OK),
        "ssl_timed_team or ubersim_ssl_bridge is not built (protobuf)")
    def test_team_programs_play_under_the_time_shim_and_the_same_seed_gives_the_same_game(self):
        out = os.path.join(self.folder, "teams")
        run = run_batch(experiment(self.folder, TEAM_PROGRAMS), "--out", out)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        games = rows(out)
        self.assertEqual(len(games), 2)
        for g in games:
            self.assertEqual(g["status"], "ok", g)
            self.assertGreater(float(g["sim_time"]), 4.0)
            self.assertGreater(float(g["speed"]), 0.0)
            # Neither team was dropped; each program ran until the bridge stopped
            # it at the game's end (SIGTERM: 143); the shim found nothing to name.
            self.assertEqual((g["yellow_without_control"], g["blue_without_control"]),
                             ("0.0", "0.0"), g)
            self.assertEqual((g["yellow_team_status"], g["blue_team_status"]), ("143", "143"), g)
            self.assertEqual(g["timeshim_problems"], "0", g)
            # The bridge hosted them (their CPU is the bridge's: it reaps them).
            self.assertIn("ssl_bridge", results_module.cpu_by_process(g))
            with open(os.path.join(g["log_dir"], "ssl_bridge.log")) as f:
                bridge = f.read()
            for team in ("yellow", "blue"):
                self.assertIn(f"registered as timed sync client ssl_bridge_{team}", bridge)
            with open(os.path.join(g["log_dir"], "team_yellow.log")) as f:
                self.assertIn("loop 200 steady 4.000000000", f.read())  # its clock: sim time
        # The same seed: the same game, event for event, and the same team output.
        for column in results_module.GAME_OUTCOME_COLUMNS + ["event_types"]:
            self.assertEqual(games[0][column], games[1][column], column)
        logs = []
        for g in games:
            with open(os.path.join(g["log_dir"], "events.jsonl")) as f:
                events = [line for line in f if '"result"' not in line]
            with open(os.path.join(g["log_dir"], "team_yellow.log")) as f:
                logs.append((events, f.read()))
        self.assertEqual(logs[0], logs[1])
        self.assertEqual(ubersim_processes_under(self.folder), [])

    @unittest.skipUnless(os.access(os.path.join(BUILD, "bin", "ubersim_ssl_bridge"), os.X_OK),
                         "ubersim_ssl_bridge is not built (protobuf)")
    def test_a_team_program_that_exits_under_the_time_shim_fails_its_game(self):
        text = TEAM_PROGRAMS.replace("SWEEP = vision.LATENCY 0.035 0.035\n", "").replace(
            'YELLOW = team "{bin}/ssl_timed_team --team {team}"',
            "YELLOW = team \"sh -c 'sleep 2; echo yellow gives up; exit 7'\"")
        out = os.path.join(self.folder, "out")
        run = run_batch(experiment(self.folder, text), "--out", out)
        self.assertEqual(run.returncode, 3, run.stdout + run.stderr)
        (g,) = rows(out)
        self.assertEqual(g["status"], "failed", g)
        # sleep 2 is 2 s of sim time: the program ends then, on the group's clock.
        self.assertIn("yellow's team program exited with status 7 at sim time 2.000 s, before "
                      "the game ended (see team_yellow.log)", g["reason"])
        self.assertEqual((g["yellow_team_status"], g["blue_team_status"]), ("7", "143"), g)
        with open(os.path.join(g["log_dir"], "team_yellow.log")) as f:
            self.assertIn("yellow gives up", f.read())
        self.assertEqual(ubersim_processes_under(self.folder), [])

    def test_a_crashing_team_program_fails_its_game_with_logs_and_the_batch_goes_on(self):
        text = SHORT.replace("YELLOW = demo", 'YELLOW = "sh -c \'echo yellow crashes; exit 7\'"')
        out = os.path.join(self.folder, "out")
        run = run_batch(experiment(self.folder, text), "--out", out)
        self.assertEqual(run.returncode, 3, run.stdout + run.stderr)
        games = rows(out)
        self.assertEqual(len(games), 2)  # both games were run
        for g in games:
            self.assertEqual(g["status"], "failed")
            self.assertIn("yellow exited with status 7", g["reason"])
            with open(os.path.join(g["log_dir"], "yellow.log")) as f:
                self.assertIn("yellow crashes", f.read())
        self.assertIn("failed", run.stderr)
        self.assertEqual(ubersim_processes_under(self.folder), [])

    def test_a_team_stopped_mid_game_in_sync_mode_makes_the_game_degraded_exit_4(self):
        # One sync game; its yellow demo team gets SIGSTOP once the game runs, so
        # the radio emulator drops it after 1 s of wall time; SIGCONT once the
        # drop is in radio.log, and it registers again (rejoins). 120 s of game:
        # a sync game runs at ~25x, so a shorter one could end before this test,
        # descheduled on a busy machine, stopped yellow.
        text = SHORT.replace("MODE = fast", "MODE = sync").replace(
            "GAMES_PER_POINT = 2", "GAMES_PER_POINT = 1").replace(
            "GAME_LENGTH = 4", "GAME_LENGTH = 120")
        out = os.path.join(self.folder, "out")
        batch = subprocess.Popen([BATCH, "run", experiment(self.folder, text), "--out", out,
                                  "--build-dir", BUILD, "-q"],
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        game = os.path.join(out, "games", "0000")
        try:
            yellow = self.wait_for(lambda: self.running_game_team(game, "yellow"), "yellow's start")
            self.wait_for(lambda: self.log_has(game, "events.jsonl", '"NORMAL_START"'),
                          "the kick-off")
            os.kill(yellow, signal.SIGSTOP)
            try:
                self.wait_for(lambda: self.log_has(game, "radio.log", "sync client dropped"),
                              "the drop")
            finally:
                os.kill(yellow, signal.SIGCONT)
            stdout, stderr = batch.communicate(timeout=120)
        finally:
            if batch.poll() is None:
                batch.kill()
        self.assertEqual(batch.returncode, 4, stdout + stderr)
        (g,) = rows(out)
        self.assertEqual(g["status"], "degraded", g)
        self.assertIn("yellow's sync client 'demo_yellow' was dropped 1 time", g["reason"])
        lost = float(g["yellow_without_control"])
        self.assertGreater(lost, 0.0, g)
        self.assertLess(lost, float(g["sim_time"]), g)
        self.assertEqual(float(g["blue_without_control"]), 0.0, g)
        self.assertIn("1 of 1 games degraded", stderr)
        self.assertIn("1 degraded", stdout)  # the summary line of the point
        with open(os.path.join(out, "summary.csv")) as f:
            (point,) = list(csv.DictReader(f))
        self.assertEqual((point["degraded"], point["failed"]), ("1", "0"))
        # The referee's result line says so too, with the same time without control.
        with open(os.path.join(game, "events.jsonl")) as f:
            result = [line for line in f if '"result"' in line][-1]
        self.assertIn('"degraded": [{"team": "yellow", "client": "demo_yellow"', result)
        self.assertEqual(ubersim_processes_under(self.folder), [])

    def running_game_team(self, game, team):
        for pid, command in processes_mentioning(game).items():
            if "ubersim_demo_team" in command and f"--team {team}" in command:
                return pid
        return None

    @staticmethod
    def log_has(game, name, text):
        try:
            with open(os.path.join(game, name), errors="replace") as f:
                return text in f.read()
        except OSError:
            return False

    def wait_for(self, condition, what, seconds=60):
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            value = condition()
            if value:
                return value
            time.sleep(0.05)
        self.fail(f"no {what} within {seconds} s")

    def start_long_games(self):
        """The short experiment with 600 s games, running in the background: (process, out)."""
        text = SHORT.replace("GAME_LENGTH = 4", "GAME_LENGTH = 600")
        out = os.path.join(self.folder, "out")
        batch = subprocess.Popen([BATCH, "run", experiment(self.folder, text), "--out", out,
                                  "--build-dir", BUILD, "-q"],
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        return batch, out

    def test_ctrl_c_stops_every_game_and_leaves_nothing_running(self):
        batch, out = self.start_long_games()
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:  # wait until both games' referees run
            if len([p for p in ubersim_processes_under(self.folder)
                    if "ubersim_referee" in p]) == 2:
                break
            time.sleep(0.2)
        else:
            batch.kill()
            self.fail("the games did not start: " + "\n".join(ubersim_processes_under(self.folder)))
        time.sleep(1)
        start = time.monotonic()
        batch.send_signal(signal.SIGINT)
        _, stderr = batch.communicate(timeout=20)
        self.assertEqual(batch.returncode, 130, stderr)
        self.assertLess(time.monotonic() - start, 6.0)
        self.assertIn("interrupted", stderr)
        self.assertEqual(ubersim_processes_under(self.folder), [])

    def test_ctrl_c_keeps_the_finished_games_marks_the_rest_stopped_and_summarizes(self):
        # Three games one at a time (a few s each): Ctrl-C once game 0 has
        # finished and game 1 is under way.
        text = SHORT.replace("GAMES_PER_POINT = 2", "GAMES_PER_POINT = 3").replace(
            "GAME_LENGTH = 4", "GAME_LENGTH = 20")
        out = os.path.join(self.folder, "out")
        batch = subprocess.Popen([BATCH, "run", experiment(self.folder, text), "--out", out,
                                  "--build-dir", BUILD, "-q", "-j", "1"],
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        deadline = time.monotonic() + 60
        while not os.path.exists(os.path.join(out, "games", "0000", "result.json")):
            if time.monotonic() > deadline or batch.poll() is not None:
                batch.kill()
                self.fail("game 0 did not finish: " + batch.communicate()[1])
            time.sleep(0.1)
        game_1 = os.path.join(out, "games", "0001") + "/"
        while not [p for p in ubersim_processes_under(game_1) if "ubersim_referee" in p]:
            if time.monotonic() > deadline or batch.poll() is not None:
                batch.kill()
                self.fail("game 1 did not start: " + batch.communicate()[1])
            time.sleep(0.05)
        batch.send_signal(signal.SIGINT)
        time.sleep(0.2)
        batch.send_signal(signal.SIGINT)  # an impatient user: changes nothing
        stdout, stderr = batch.communicate(timeout=20)
        self.assertEqual(batch.returncode, 130, stdout + stderr)
        games = rows(out)
        self.assertEqual([g["game"] for g in games], ["0", "1", "2"], games)
        self.assertEqual(games[0]["status"], "ok", games[0])
        self.assertGreater(float(games[0]["sim_time"]), 20.0)
        self.assertEqual(games[0]["log_dir"], os.path.join(out, "games", "0000"))
        for g in games[1:]:
            self.assertEqual(g["status"], "stopped", g)
            self.assertIn("interrupted", g["reason"])
        # The summary of the finished game, printed and written; where they are.
        self.assertIn("point 0 (all games): 1 of 1 games finished", stdout)
        with open(os.path.join(out, "summary.csv")) as f:
            self.assertEqual([s["games"] for s in csv.DictReader(f)], ["1"])
        self.assertIn(os.path.join(out, "results.csv"), stderr)
        self.assertIn("summary.txt", stderr)
        self.assertEqual(ubersim_processes_under(self.folder), [])

    def test_sigterm_before_any_game_finished_marks_every_game_stopped_exit_143(self):
        batch, out = self.start_long_games()
        deadline = time.monotonic() + 30
        while not [p for p in ubersim_processes_under(self.folder) if "ubersim_referee" in p]:
            if time.monotonic() > deadline:
                batch.kill()
                self.fail("the games did not start")
            time.sleep(0.2)
        batch.send_signal(signal.SIGTERM)
        stdout, stderr = batch.communicate(timeout=20)
        self.assertEqual(batch.returncode, 143, stdout + stderr)
        self.assertEqual([g["status"] for g in rows(out)], ["stopped", "stopped"])
        self.assertIn("0 of 2 games had finished", stderr)
        self.assertEqual(ubersim_processes_under(self.folder), [])


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], *sys.argv[3:]], verbosity=2)
