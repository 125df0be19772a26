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
# The fuzz targets, ~10 s each, in a clang build of their own (docs/fuzzing.md): at -O0,
# half the CPU of tools/fuzz.sh's -O1 build for campaigns (build-fuzz/), so in a folder of
# its own. It runs beside the tests at the lowest priority (nice 19): most tests wait in
# real time, and their programs get the cores whenever they want them. Its output goes to a log.
fuzz_build=""
if [ $# -eq 0 ] && command -v clang++ >/dev/null 2>&1; then
  fuzz_dir=${UBERSIM_TEST_FUZZ_BUILD_DIR:-$root/build-fuzz-test}
  mkdir -p "$fuzz_dir/tmp"
  fuzz_log=$fuzz_dir/build.log
  TMPDIR=$fuzz_dir/tmp UBERSIM_FUZZ_BUILD_DIR=$fuzz_dir UBERSIM_FUZZ_OPTIMIZATION=-O0 \
    nice -n 19 "$root/tools/fuzz.sh" --build >"$fuzz_log" 2>&1 &
  fuzz_build=$!
  trap 'kill "$fuzz_build" 2>/dev/null' EXIT
  echo "tools/test.sh: building the fuzz targets beside the tests (log: $fuzz_log)"
fi
(cd "${UBERSIM_BUILD_DIR:-$root/build}" && ctest --output-on-failure -j "$(nproc)" "$@") || status=$?
if [ -n "$fuzz_build" ]; then
  if wait "$fuzz_build"; then
    (cd "$fuzz_dir" && ctest -L fuzz --output-on-failure -j "$(nproc)") || status=$?
  else
    echo "tools/test.sh: the fuzz build failed; the end of its log ($fuzz_log):" >&2
    tail -n 40 "$fuzz_log" >&2
    status=1
  fi
  trap - EXIT
fi
if [ -n "$(ls -A "$run_tmp")" ]; then
  echo "tools/test.sh: the tests left these in $run_tmp (a failed test keeps its folder):" >&2
  ls -A "$run_tmp" >&2
  [ "$status" -ne 0 ] || status=1
else
  rmdir "$run_tmp"
fi
exit "$status"
