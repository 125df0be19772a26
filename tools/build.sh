#!/usr/bin/env bash
# Configures and builds ubersim into build/ (Release). Used by the quick-start
# commands; run it after changing code.
#   tools/build.sh                   everything: programs, tests, benchmarks, fuzz replays
#   tools/build.sh TARGET...         only these CMake targets and what they need
#                                    (tools/demo.sh builds only the programs the demo runs)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir=${UBERSIM_BUILD_DIR:-$root/build}
for target in "$@"; do
  [[ $target =~ ^[A-Za-z0-9_.+-]+$ ]] || { echo "build.sh: '$target' is not a CMake target name" >&2; exit 2; }
done
launcher=()
# ccache, where installed, makes rebuilds of several checkouts cheap; the build never needs it.
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache); fi
cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DUBERSIM_WERROR=ON "${launcher[@]}" >/dev/null
targets=()
[ $# -eq 0 ] || targets=(--target "$@")
cmake --build "$build_dir" -j "$(nproc)" "${targets[@]}"
