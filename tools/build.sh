#!/usr/bin/env bash
# Configures and builds ubersim into build/ (Release). Used by the quick-start
# commands; run it after changing code.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir=${UBERSIM_BUILD_DIR:-$root/build}
cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DUBERSIM_WERROR=ON >/dev/null
cmake --build "$build_dir" -j "$(nproc)"
