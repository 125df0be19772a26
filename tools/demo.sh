#!/usr/bin/env bash
# Quick start, first command: install what is missing, build the programs the
# demo runs (tools/test.sh builds the rest: tests, benchmarks, fuzz replays),
# and start a refereed demo game: both demo teams, the automatic referee (a new
# game starts when one is over, until Ctrl-C) and the browser viewer, whose
# address is printed first and which opens in the desktop's browser when there
# is a desktop session. Ctrl-C stops everything.
# Extra options go to tools/launch.sh (e.g. --field division_a, --speed 4,
# --game-length 120).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
# What tools/launch.sh starts for the demo, and ubersim_logger, which it looks for.
demo_programs=(ubersim_physics ubersim_vision ubersim_radio ubersim_demo_team ubersim_referee
  ubersim_viewer ubersim_logger)
"$root/tools/install-deps.sh"
"$root/tools/build.sh" "${demo_programs[@]}"
exec "$root/tools/launch.sh" --demo both --referee --repeat-games --open-viewer "$@"
