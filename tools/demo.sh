#!/usr/bin/env bash
# Quick start, first command: install what is missing, build, and start the
# simulator with a demo game (both demo teams) and the browser viewer: its
# address is printed first, and it opens in the desktop's browser when there
# is a desktop session. Ctrl-C stops everything.
# Extra options go to tools/launch.sh (e.g. --field division_a, --speed 4).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/install-deps.sh"
"$root/tools/build.sh"
exec "$root/tools/launch.sh" --demo both --open-viewer "$@"
