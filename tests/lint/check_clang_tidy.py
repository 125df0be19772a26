#!/usr/bin/env python3
"""Lint as a test: clang-tidy, with the checks .clang-tidy enables, finds nothing.

Runs clang-tidy on every translation unit of the programs and libraries in
the build's compile_commands.json (files under SOURCE_DIR, not under the build
folder; not tests/, fuzz/ or a bench/ folder, to keep CI's time), in
parallel, one process per core. Translation units compiled with the same
flags are checked in batches: one clang-tidy run on a file in a temporary
folder that includes up to BATCH_SIZE of them, so the system headers they
share are parsed and matched once (most of clang-tidy's time); where a batch
does not compile as one file (a file defines a name an earlier one defined
too), the files with errors are checked in a batch of their own and the
others again without them. Our headers count too: a finding in any
file under SOURCE_DIR is reported; system headers, fetched and generated code
(the build folder) are not. Each finding is printed once as

    path/to/file.cpp:LINE: check-name: message

and the test fails when there is any. Exit 77 (skipped) when clang-tidy is
not installed. Run it alone with `ctest -R test_clang_tidy` or

    tests/lint/check_clang_tidy.py SOURCE_DIR BUILD_DIR [FILE...]

(FILE...: only these translation units, e.g. the ones you changed; any file of
ours in compile_commands.json, tests too).
"""

import itertools
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

SKIP = 77
BATCH_SIZE = 30
# Not checked unless named: clang-tidy costs 2-30 s of CPU per translation unit, and
# tests, fuzz targets and benchmarks would more than double the test's time.
NOT_CHECKED_BY_DEFAULT = re.compile(r"^(tests|fuzz)/|(^|/)bench/")
FINDING = re.compile(r"^(?P<file>[^\s:][^:]*):(?P<line>\d+):\d+: (?:warning|error): "
                     r"(?P<message>.*) \[(?P<check>[^\]]+)\]$")


def usage_error(message):
    print(f"check_clang_tidy: {message}", file=sys.stderr)
    print("usage: check_clang_tidy.py SOURCE_DIR BUILD_DIR [FILE...]", file=sys.stderr)
    sys.exit(2)


def is_under(path, folder):
    return os.path.commonpath([path, folder]) == folder


def our_translation_units(source_dir, build_dir):
    """Every source file of ours the build compiles, once, with its compile_commands.json
    entry (a file compiled by two targets is checked with the first command, as clang-tidy
    itself does)."""
    database = os.path.join(build_dir, "compile_commands.json")
    if not os.path.isfile(database):
        usage_error(f"{database} not found (configure the build first: tools/build.sh)")
    with open(database, encoding="utf-8") as stream:
        entries = json.load(stream)
    units = {}  # a dict keeps the database's order
    for entry in entries:
        path = os.path.realpath(os.path.join(entry.get("directory", ""), entry["file"]))
        if is_under(path, source_dir) and not is_under(path, build_dir) and path not in units:
            units[path] = entry
    return units


def compile_arguments(entry):
    if "arguments" in entry:
        return list(entry["arguments"])
    return shlex.split(entry["command"])


def flags_without_file(entry):
    """The entry's compiler command without its source and output file: units with the
    same flags can share a batch."""
    arguments = compile_arguments(entry)
    kept = []
    skip_next = False
    for argument in arguments:
        if skip_next:
            skip_next = False
        elif argument == "-o":
            skip_next = True
        elif argument != entry["file"] and not argument.startswith("-o"):
            kept.append(argument)
    return entry.get("directory", ""), tuple(kept)


def nearest_config(path, source_dir):
    """The .clang-tidy clang-tidy would use for PATH (the nearest one above it)."""
    folder = os.path.dirname(path)
    while is_under(folder, source_dir):
        candidate = os.path.join(folder, ".clang-tidy")
        if os.path.isfile(candidate):
            return candidate
        folder = os.path.dirname(folder)
    return None


def header_filter(source_dir):
    """Findings in any file under SOURCE_DIR are shown (our headers count); the ones in
    the build folder (generated and fetched code) are dropped after the run."""
    return "^" + re.sub(r"([.^$|()\[\]*+?{}\\])", r"\\\1", source_dir) + "/"


MAIN = re.compile(r"^\s*int\s+main\s*\(", re.MULTILINE)


def defines_main(path):
    with open(path, encoding="utf-8", errors="replace") as stream:
        return MAIN.search(stream.read()) is not None


def make_batches(units, source_dir, batch_size):
    """Units with the same flags and configuration, up to batch_size in a batch and at
    most one program's main() (two would not compile as one file, and the batch would be
    split and checked again): (units, their common compile_commands.json entry,
    configuration) per batch."""
    groups = {}
    for path, entry in units.items():
        key = (flags_without_file(entry), nearest_config(path, source_dir))
        groups.setdefault(key, []).append((path, entry))
    batches = []
    for (_, config), members in groups.items():
        mains = [member for member in members if defines_main(member[0])]
        others = [member for member in members if not defines_main(member[0])]
        count = max(len(mains), -(-len(members) // batch_size))
        chunks = [[main] for main in mains] + [[] for _ in range(count - len(mains))]
        for member in others:
            min(chunks, key=len).append(member)
        for chunk in chunks:
            if chunk:
                batches.append(([path for path, _ in chunk], chunk[0][1], config))
    return batches


def run_clang_tidy(clang_tidy, database_dir, build_dir, headers, config, unit):
    """clang-tidy on one file: its findings outside the build folder, the files with a
    compile error, and the tail of its output when it failed without findings."""
    command = [clang_tidy, "--quiet", "-p", database_dir, f"--header-filter={headers}"]
    if config:
        command.append(f"--config-file={config}")
    result = subprocess.run(command + [unit], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, check=False)
    findings = set()
    error_files = set()
    for line in result.stdout.splitlines():
        match = FINDING.match(line)
        if match:
            path = os.path.realpath(match["file"])
            if match["check"] == "clang-diagnostic-error":
                error_files.add(path)
            if not is_under(path, build_dir) and not is_under(path, database_dir):
                findings.add((path, int(match["line"]), match["check"], match["message"]))
    problem = None
    if result.returncode != 0 and not findings:
        problem = (result.stdout + result.stderr).strip().splitlines()[-5:]
        error_files.add(unit)
    return findings, error_files, problem


class Batches:
    """Runs clang-tidy on a batch: one file in a folder of its own under TMPDIR (a test
    writes only there) that includes the batch's units, with a compile database of its own
    holding the units' common command."""

    def __init__(self, clang_tidy, build_dir, headers):
        self.clang_tidy = clang_tidy
        self.build_dir = build_dir
        self.headers = headers
        self.folder = tempfile.mkdtemp(prefix="clang-tidy-batches.")
        self.numbers = itertools.count()  # batch folders
        self.runs = itertools.count()

    def check(self, batch):
        """(findings, [(unit, problem)]) of a batch's units. Where the batch does not
        compile as one file (a unit defines a name an earlier one defined too), the units
        with errors are checked again in a batch of their own, the others without them; a
        unit alone is checked with its own command, as the build compiles it."""
        units, entry, config = batch
        if len(units) == 1:
            next(self.runs)
            findings, _, problem = run_clang_tidy(self.clang_tidy, self.build_dir,
                                                  self.build_dir, self.headers, config, units[0])
            return findings, [(units[0], problem)] if problem else []
        findings, error_files, _ = self.run(units, entry, config)
        if not error_files:
            return findings, []
        with_errors = [unit for unit in units if unit in error_files]
        if units[0] in error_files or not with_errors:
            # The first unit's own error, or one in a header: halves, down to single units.
            middle = 1 if units[0] in error_files else len(units) // 2
            parts = [units[:middle], units[middle:]]
        else:
            parts = [[unit for unit in units if unit not in error_files], with_errors]
        findings, problems = set(), []
        for part in parts:
            part_findings, part_problems = self.check((part, entry, config))
            findings |= part_findings
            problems += part_problems
        return findings, problems

    def run(self, units, entry, config):
        next(self.runs)
        folder = os.path.join(self.folder, str(next(self.numbers)))
        os.makedirs(folder)
        batch = os.path.join(folder, "batch.cpp")
        with open(batch, "w", encoding="utf-8") as stream:
            stream.writelines(f'#include "{unit}"\n' for unit in units)
        directory, flags = flags_without_file(entry)
        with open(os.path.join(folder, "compile_commands.json"), "w",
                  encoding="utf-8") as stream:
            json.dump([{"directory": directory, "file": batch,
                        "arguments": list(flags) + ["-c", batch]}], stream)
        return run_clang_tidy(self.clang_tidy, folder, self.build_dir, self.headers, config,
                              batch)


def main():
    if len(sys.argv) < 3:
        usage_error("needs SOURCE_DIR and BUILD_DIR")
    source_dir = os.path.realpath(sys.argv[1])
    build_dir = os.path.realpath(sys.argv[2])
    clang_tidy = shutil.which("clang-tidy")
    if clang_tidy is None:
        print("check_clang_tidy: skipped, clang-tidy is not installed "
              "(tools/install-deps.sh installs it)")
        return SKIP
    units = our_translation_units(source_dir, build_dir)
    batch_size = BATCH_SIZE
    if len(sys.argv) > 3:
        wanted = [os.path.realpath(path) for path in sys.argv[3:]]
        unknown = [path for path in wanted if path not in units]
        if unknown:
            usage_error("not a translation unit in compile_commands.json: " + " ".join(unknown))
        units = {path: units[path] for path in wanted}
        batch_size = 1  # the files you name, each exactly as the build compiles it
    else:
        units = {path: entry for path, entry in units.items()
                 if not NOT_CHECKED_BY_DEFAULT.search(os.path.relpath(path, source_dir))}
    if not units:
        usage_error("no translation unit of ours in compile_commands.json")
    headers = header_filter(source_dir)
    batches = make_batches(units, source_dir, batch_size)
    batches.sort(key=lambda batch: -len(batch[0]))  # the longest first: the cores end together
    runner = Batches(clang_tidy, build_dir, headers)
    workers = len(os.sched_getaffinity(0))
    try:
        with ThreadPoolExecutor(max_workers=workers) as pool:
            results = list(pool.map(runner.check, batches))
    finally:
        shutil.rmtree(runner.folder, ignore_errors=True)
    return report(source_dir, clang_tidy, len(units), next(runner.runs), results)


def report(source_dir, clang_tidy, unit_count, run_count, results):
    findings = set()
    failed_units = []
    for batch_findings, problems in results:
        findings |= batch_findings
        failed_units += problems
    for path, line, check, message in sorted(findings):
        print(f"{os.path.relpath(path, source_dir)}:{line}: {check}: {message}")
    for unit, problem in failed_units:
        print(f"clang-tidy failed on {os.path.relpath(unit, source_dir)}:")
        print("\n".join("    " + text for text in problem))
    files = len({finding[0] for finding in findings})
    version = subprocess.run([clang_tidy, "--version"], stdout=subprocess.PIPE, text=True,
                             check=False).stdout
    version = next((text.strip() for text in version.splitlines() if "version" in text), "")
    print(f"check_clang_tidy: {len(findings)} findings in {files} files, "
          f"{len(failed_units)} translation units clang-tidy could not check, "
          f"{unit_count} translation units checked in {run_count} runs "
          f"({version}; checks from .clang-tidy)")
    if findings:
        print("Fix each one, or, where the code is right, silence that line with "
              "// NOLINT(check-name) and a comment saying why.")
    return 1 if findings or failed_units else 0


if __name__ == "__main__":
    sys.exit(main())
