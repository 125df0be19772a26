#!/usr/bin/env bash
# Quick start, second command: install what is missing, build, run every test.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/install-deps.sh"
"$root/tools/build.sh"
(cd "${UBERSIM_BUILD_DIR:-$root/build}" && ctest --output-on-failure -j "$(nproc)" "$@")
# The fuzz targets, ~10 s each, in a clang build of their own (docs/fuzzing.md).
if [ $# -eq 0 ] && command -v clang++ >/dev/null 2>&1; then
  "$root/tools/fuzz.sh" --build
  (cd "${UBERSIM_FUZZ_BUILD_DIR:-$root/build-fuzz}" && ctest -L fuzz --output-on-failure -j "$(nproc)")
fi
