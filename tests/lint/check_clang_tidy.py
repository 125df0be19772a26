#!/usr/bin/env python3
"""Lint as a test: clang-tidy, with the checks .clang-tidy enables, finds nothing.

Runs clang-tidy on every translation unit of the programs and libraries in
the build's compile_commands.json (files under SOURCE_DIR, not under the build
folder; not tests/, fuzz/ or a bench/ folder, to keep CI's time), in
parallel, one process per core. Our headers count too: a finding in any
file under SOURCE_DIR is reported; system headers, fetched and generated code
(the build folder) are not. Each finding is printed once as

    path/to/file.cpp:LINE: check-name: message

and the test fails when there is any. Exit 77 (skipped) when clang-tidy is
not installed. Run it alone with `ctest -R test_clang_tidy` or

    tests/lint/check_clang_tidy.py SOURCE_DIR BUILD_DIR [FILE...]

(FILE...: only these translation units, e.g. the ones you changed; any file of
ours in compile_commands.json, tests too).
"""

import json
import os
import re
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

SKIP = 77
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
    """Every source file of ours the build compiles, once (a file compiled by two targets
    is checked with the first command, as clang-tidy itself does)."""
    database = os.path.join(build_dir, "compile_commands.json")
    if not os.path.isfile(database):
        usage_error(f"{database} not found (configure the build first: tools/build.sh)")
    with open(database, encoding="utf-8") as stream:
        entries = json.load(stream)
    units = {}  # a dict keeps the database's order
    for entry in entries:
        path = os.path.realpath(os.path.join(entry.get("directory", ""), entry["file"]))
        if is_under(path, source_dir) and not is_under(path, build_dir):
            units[path] = None
    return list(units)


def header_filter(source_dir):
    """Findings in any file under SOURCE_DIR are shown (our headers count); the ones in
    the build folder (generated and fetched code) are dropped after the run."""
    return "^" + re.sub(r"([.^$|()\[\]*+?{}\\])", r"\\\1", source_dir) + "/"


def run_one(clang_tidy, build_dir, headers, unit):
    """clang-tidy on one translation unit: its findings outside the build folder, and the
    tail of its output when it failed without findings (it could not compile the file)."""
    result = subprocess.run(
        [clang_tidy, "--quiet", "-p", build_dir, f"--header-filter={headers}", unit],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, check=False)
    findings = set()
    for line in result.stdout.splitlines():
        match = FINDING.match(line)
        if match:
            path = os.path.realpath(match["file"])
            if not is_under(path, build_dir):
                findings.add((path, int(match["line"]), match["check"], match["message"]))
    problem = None
    if result.returncode != 0 and not findings:
        problem = (result.stdout + result.stderr).strip().splitlines()[-5:]
    return unit, findings, problem


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
    if len(sys.argv) > 3:
        wanted = [os.path.realpath(path) for path in sys.argv[3:]]
        unknown = [path for path in wanted if path not in units]
        if unknown:
            usage_error("not a translation unit in compile_commands.json: " + " ".join(unknown))
        units = wanted
    else:
        units = [unit for unit in units
                 if not NOT_CHECKED_BY_DEFAULT.search(os.path.relpath(unit, source_dir))]
    if not units:
        usage_error("no translation unit of ours in compile_commands.json")
    headers = header_filter(source_dir)
    workers = len(os.sched_getaffinity(0))
    with ThreadPoolExecutor(max_workers=workers) as pool:
        results = list(pool.map(lambda unit: run_one(clang_tidy, build_dir, headers, unit), units))
    return report(source_dir, clang_tidy, len(units), results)


def report(source_dir, clang_tidy, unit_count, results):
    findings = set()
    failed_units = []
    for unit, unit_findings, problem in results:
        findings |= unit_findings
        if problem:
            failed_units.append((unit, problem))
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
          f"{unit_count} translation units checked ({version}; checks from .clang-tidy)")
    if findings:
        print("Fix each one, or, where the code is right, silence that line with "
              "// NOLINT(check-name) and a comment saying why.")
    return 1 if findings or failed_units else 0


if __name__ == "__main__":
    sys.exit(main())
