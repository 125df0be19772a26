#!/usr/bin/env bash
# Configures and builds ubersim into build/ (Release). Used by the quick-start
# commands; run it after changing code.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir=${UBERSIM_BUILD_DIR:-$root/build}
launcher=()
# ccache, where installed, makes rebuilds of several checkouts cheap; the build never needs it.
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache); fi
cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DUBERSIM_WERROR=ON "${launcher[@]}" >/dev/null
cmake --build "$build_dir" -j "$(nproc)"
