#!/usr/bin/env bash
# Quick start, second command: install what is missing, build, run every test.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/install-deps.sh"
"$root/tools/build.sh"
# Every test writes only into a folder of its own under TMPDIR, removed when it
# passes (cmake/UbersimTest.cmake): the run gets a fresh TMPDIR, and anything
# left in it at the end fails the run.
run_tmp=$(mktemp -d "${TMPDIR:-/tmp}/ubersim-test-run.XXXXXX")
export TMPDIR=$run_tmp
status=0
(cd "${UBERSIM_BUILD_DIR:-$root/build}" && ctest --output-on-failure -j "$(nproc)" "$@") || status=$?
# The fuzz targets, ~10 s each, in a clang build of their own (docs/fuzzing.md).
if [ $# -eq 0 ] && command -v clang++ >/dev/null 2>&1; then
  "$root/tools/fuzz.sh" --build || status=$?
  (cd "${UBERSIM_FUZZ_BUILD_DIR:-$root/build-fuzz}" && ctest -L fuzz --output-on-failure -j "$(nproc)") ||
    status=$?
fi
if [ -n "$(ls -A "$run_tmp")" ]; then
  echo "tools/test.sh: the tests left these in $run_tmp (a failed test keeps its folder):" >&2
  ls -A "$run_tmp" >&2
  [ "$status" -ne 0 ] || status=1
else
  rmdir "$run_tmp"
fi
exit "$status"
