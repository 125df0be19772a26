#!/usr/bin/env bash
# Runs one test with TMPDIR set to a folder of its own, made under the TMPDIR
# ctest runs with (tools/test.sh gives each run a fresh one and fails when
# anything is left in it). The folder is removed when the test passes and
# kept, with its path printed, when it fails.
# Usage: own_tmpdir.sh TEST_NAME COMMAND [ARGS...]
set -u
name=$1
shift
dir=$(mktemp -d "${TMPDIR:-/tmp}/$name.XXXXXX") || exit 1
# In the foreground: a command started with & would have SIGINT ignored, and
# tests send SIGINT on purpose. (On a timeout ctest kills the whole tree.)
TMPDIR=$dir "$@"
status=$?
# An empty folder tells nothing: removed too (a test may pass on its output
# with a non-zero exit, PASS_REGULAR_EXPRESSION).
if [ "$status" -eq 0 ] || [ -z "$(ls -A "$dir")" ]; then
  rm -rf "$dir"
else
  echo "$name: exit $status, its files are kept in $dir" >&2
fi
exit "$status"
