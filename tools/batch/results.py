"""What a batch writes: results.csv (one row per game), summary.csv and
summary.txt (one row per sweep point, with 95 % confidence intervals), and a
gnuplot figure of the score difference against each swept parameter."""
import csv
import math
import os
import shutil
import subprocess

GAME_COLUMNS = [
    "status", "yellow_goals", "blue_goals", "score_difference", "yellow_shots", "blue_shots",
    "yellow_possession", "blue_possession", "yellow_fouls", "blue_fouls",
    "yellow_yellow_cards", "blue_yellow_cards", "yellow_red_cards", "blue_red_cards", "events",
    "sim_time", "wall_time", "speed", "yellow_without_control", "blue_without_control",
    "vision_frames_lost", "yellow_team_status", "blue_team_status", "timeshim_problems",
    "reason", "log_dir",
]
# Columns that depend only on what happened in the game (not on the machine):
# two runs of the same experiment in sync mode give the same values.
GAME_OUTCOME_COLUMNS = GAME_COLUMNS[:GAME_COLUMNS.index("sim_time") + 1]

# The figures summary.csv gives the mean and 95 % CI of, per sweep point.
SUMMARY_FIGURES = ("score_difference", "yellow_goals", "blue_goals", "yellow_shots", "blue_shots",
                   "yellow_possession", "yellow_fouls", "blue_fouls", "speed")

# Two-sided 95 % quantiles of Student's t for 1..30 degrees of freedom.
T95 = [12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179,
       2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064,
       2.060, 2.056, 2.052, 2.048, 2.045, 2.042]


def cpu_by_process(row):
    """{process: CPU seconds} from a results.csv row's cpu_seconds column."""
    pairs = (item.split(":") for item in row.get("cpu_seconds", "").split())
    return {name: float(seconds) for name, seconds in pairs}


def read_results(out_dir):
    with open(os.path.join(out_dir, "results.csv")) as f:
        return list(csv.DictReader(f))


def mean_and_ci(values):
    """Mean and half width of its 95 % confidence interval (nan with one value).
    Values that are "" (a figure the game's referee does not keep) are left out."""
    values = [v for v in values if v != ""]
    n = len(values)
    if n == 0:
        return math.nan, math.nan
    mean = sum(values) / n
    if n == 1:
        return mean, math.nan
    variance = sum((v - mean) ** 2 for v in values) / (n - 1)
    t = T95[n - 2] if n - 1 <= len(T95) else 1.960
    return mean, t * math.sqrt(variance / n)


def _row(result, sweep_names):
    row = {"game": result["index"], "point": result["point"], "seed": result["seed"]}
    for name in sweep_names:
        row[name] = result["parameters"].get(name, "")
    for column in GAME_COLUMNS:
        row[column] = result.get(column, "")
    types = result.get("events_by_type", {})
    row["event_types"] = " ".join(f"{k}:{types[k]}" for k in sorted(types))
    cpu = result.get("cpu", {})
    row["cpu_seconds"] = " ".join(f"{k}:{cpu[k]}" for k in sorted(cpu))
    return row


def _columns(sweep_names):
    return ["game", "point", "seed", *sweep_names, *GAME_COLUMNS, "event_types", "cpu_seconds"]


def write_results(out_dir, results, sweep_names):
    """results.csv with every row, in game order; replaces the file atomically."""
    path = os.path.join(out_dir, "results.csv")
    with open(path + ".tmp", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=_columns(sweep_names))
        writer.writeheader()
        for result in sorted(results, key=lambda r: r["index"]):
            writer.writerow(_row(result, sweep_names))
        f.flush()
        os.fsync(f.fileno())
    os.replace(path + ".tmp", path)
    return path


class ResultsFile:
    """results.csv written as the games end: the header at once, then a row
    (flushed to disk) the moment each game's result arrives, so a runner that
    is killed loses no finished game. finish() rewrites it in game order."""

    def __init__(self, out_dir, sweep_names):
        self.out_dir, self.sweep_names = out_dir, sweep_names
        self.path = os.path.join(out_dir, "results.csv")
        self.file = open(self.path, "w", newline="")
        self.writer = csv.DictWriter(self.file, fieldnames=_columns(sweep_names))
        self.writer.writeheader()
        self._flush()

    def _flush(self):
        self.file.flush()
        os.fsync(self.file.fileno())

    def append(self, result):
        self.writer.writerow(_row(result, self.sweep_names))
        self._flush()

    def finish(self, results):
        self.file.close()
        return write_results(self.out_dir, results, self.sweep_names)


def stopped(spec):
    """The row of a game that an interrupted batch did not finish."""
    return {"index": spec["index"], "point": spec["point"], "seed": spec["seed"],
            "parameters": spec["parameters"], "status": "stopped",
            "reason": "the batch was interrupted before this game finished",
            "log_dir": spec.get("game_dir", "")}


def summarize(results, sweep_names):
    """One dict per sweep point, in point order."""
    points = {}
    for r in results:
        points.setdefault(r["point"], []).append(r)
    summary = []
    for point in sorted(points):
        games = points[point]
        # A degraded game (a team played part of it without control) is left
        # out of the statistics, like a failed one, and counted on its own.
        ok = [g for g in games if g["status"] == "ok"]
        degraded = sum(g["status"] == "degraded" for g in games)
        entry = {"point": point, "games": len(games), "failed": len(games) - len(ok) - degraded,
                 "degraded": degraded}
        for name in sweep_names:
            entry[name] = games[0]["parameters"].get(name, "")
        for key in SUMMARY_FIGURES:
            mean, ci = mean_and_ci([g[key] for g in ok])
            entry[key] = mean
            entry[key + "_ci95"] = ci
        entry["yellow_wins"] = sum(1 for g in ok if g["score_difference"] > 0)
        entry["draws"] = sum(1 for g in ok if g["score_difference"] == 0)
        entry["blue_wins"] = sum(1 for g in ok if g["score_difference"] < 0)
        summary.append(entry)
    return summary


def _format(value):
    if isinstance(value, float):
        return "nan" if math.isnan(value) else f"{value:.4g}"
    return str(value)


def write_summary(out_dir, summary, sweep_names):
    columns = ["point", *sweep_names, "games", "failed", "degraded", "yellow_wins", "draws",
               "blue_wins"]
    for key in SUMMARY_FIGURES:
        columns += [key, key + "_ci95"]
    with open(os.path.join(out_dir, "summary.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=columns)
        writer.writeheader()
        for entry in summary:
            writer.writerow({k: _format(entry[k]) for k in columns})
    lines = []
    for entry in summary:
        where = ", ".join(f"{n} = {entry[n]}" for n in sweep_names) or "all games"
        d, ci = entry["score_difference"], entry["score_difference_ci95"]
        degraded = (f" ({entry['degraded']} degraded: a team without control for part of the "
                    f"game; not in the figures)" if entry["degraded"] else "")
        lines.append(
            f"point {entry['point']} ({where}): {entry['games'] - entry['failed']} of "
            f"{entry['games']} games finished{degraded}; yellow - blue = {_format(d)} +- {_format(ci)} "
            f"(95 % CI); wins yellow/draws/blue {entry['yellow_wins']}/{entry['draws']}/"
            f"{entry['blue_wins']}; goals {_format(entry['yellow_goals'])} : "
            f"{_format(entry['blue_goals'])}; shots {_format(entry['yellow_shots'])} : "
            f"{_format(entry['blue_shots'])}; fouls {_format(entry['yellow_fouls'])} : "
            f"{_format(entry['blue_fouls'])}; speed {_format(entry['speed'])} x real time")
    with open(os.path.join(out_dir, "summary.txt"), "w") as f:
        f.write("\n".join(lines) + "\n")
    return lines


def write_figures(out_dir, summary, sweep_names):
    """score_difference_<n>.png: mean score difference with its 95 % CI against
    each swept parameter (the other sweeps pooled). Returns the files written."""
    written = []
    for n, name in enumerate(sweep_names):
        by_value = {}
        for entry in summary:
            by_value.setdefault(entry[name], []).append(entry)
        data = os.path.join(out_dir, f"score_difference_{n}.dat")
        with open(data, "w") as f:
            f.write(f"# {name}  mean_score_difference  ci95  (yellow - blue)\n")
            for i, (value, entries) in enumerate(by_value.items()):
                means = [e["score_difference"] for e in entries if not math.isnan(e["score_difference"])]
                cis = [e["score_difference_ci95"] for e in entries
                       if not math.isnan(e["score_difference_ci95"])]
                mean = sum(means) / len(means) if means else math.nan
                ci = max(cis) if cis else 0.0
                f.write(f"{i} {value} {mean} {ci}\n")
        script = os.path.join(out_dir, f"score_difference_{n}.gp")
        png = f"score_difference_{n}.png"
        with open(script, "w") as f:
            f.write(f"""# gnuplot {os.path.basename(script)} (from {out_dir}) redraws {png}
set terminal pngcairo size 800,500
set output '{png}'
set title 'Score difference (yellow - blue) against {name}, mean and 95 % CI'
set xlabel '{name}'
set ylabel 'goals, yellow - blue'
set grid
set offsets 0.3, 0.3, 0.5, 0.5
set xzeroaxis
plot '{os.path.basename(data)}' using 1:3:4:xtic(2) with yerrorbars pt 7 title 'games', \\
     '' using 1:3 with lines notitle
""")
        written.append(script)
        if shutil.which("gnuplot"):
            run = subprocess.run(["gnuplot", os.path.basename(script)], cwd=out_dir,
                                 capture_output=True, text=True)
            if run.returncode == 0:
                written.append(os.path.join(out_dir, png))
            else:
                print(f"ubersim_batch: gnuplot failed on {script}: {run.stderr.strip()}")
    return written
