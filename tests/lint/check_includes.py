#!/usr/bin/env python3
"""Lint as a test: the headers that cost the build minutes are included the cheap way.

* <spdlog/spdlog.h> only through ubersim/spdlog.hpp, which declares the fmt
  instantiation spdlog uses extern (without it every file that logs compiles
  fmt's formatting engine again: about 4 s of -O3 per file).
* <CLI/CLI.hpp> and ubersim/cli.hpp only in a file that parses a command line
  (names CLI::, add_common_options, parse_command_line, ...): CLI11 is
  header-only and costs about 4 s of -O3 in every file that includes it. A
  file that only holds the common options includes ubersim/common_options.hpp.

Usage: check_includes.py SOURCE_DIR. Prints each offending line as
path:LINE: what to include instead, and exits 1 when there is any.
"""
import os
import re
import sys

SOURCE_SUFFIXES = (".cpp", ".cc", ".hpp", ".h")
SKIPPED_FOLDERS = {".git", "third_party"}
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]')
# What a file that includes ubersim/cli.hpp must use of it.
USES_CLI = re.compile(r"CLI::|add_common_options|parse_command_line|command_line_error|"
                      r"\bin_range\(|\bat_least\(|\bgreater_than\(|\bwhole_number\(")
SPDLOG = "spdlog/spdlog.h"
SPDLOG_WRAPPER = "common/include/ubersim/spdlog.hpp"
COMMAND_LINE_PARSERS = ("CLI/CLI.hpp", "ubersim/cli.hpp")


def our_sources(source_dir):
    for folder, subfolders, files in os.walk(source_dir):
        subfolders[:] = [name for name in subfolders
                         if name not in SKIPPED_FOLDERS and not name.startswith("build")]
        for name in sorted(files):
            if name.endswith(SOURCE_SUFFIXES):
                yield os.path.join(folder, name)


def findings_of(path, relative):
    with open(path, encoding="utf-8", errors="replace") as stream:
        text = stream.read()
    for number, line in enumerate(text.splitlines(), start=1):
        match = INCLUDE.match(line)
        if not match:
            continue
        header = match[1]
        if header == SPDLOG and relative != SPDLOG_WRAPPER:
            yield f"{relative}:{number}: include \"ubersim/spdlog.hpp\", not <{header}>"
        if header in COMMAND_LINE_PARSERS and not USES_CLI.search(text):
            yield (f"{relative}:{number}: parses no command line: include "
                   f"\"ubersim/common_options.hpp\", not {header}")


def main():
    if len(sys.argv) != 2:
        print("usage: check_includes.py SOURCE_DIR", file=sys.stderr)
        return 2
    source_dir = os.path.realpath(sys.argv[1])
    findings = []
    for path in our_sources(source_dir):
        findings.extend(findings_of(path, os.path.relpath(path, source_dir)))
    for finding in findings:
        print(finding)
    print(f"check_includes: {len(findings)} finding(s)")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
