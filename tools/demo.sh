#!/usr/bin/env bash
# Quick start, first command: install what is missing, build, and start the
# simulator with a demo game (Ctrl-C stops everything).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/install-deps.sh"
"$root/tools/build.sh"
if [ ! -x "${UBERSIM_BUILD_DIR:-$root/build}/bin/ubersim_physics" ] || [ ! -x "$root/tools/launch.sh" ]; then
  echo "demo: the physics server and launch script are not built yet (issues 3 and 6);" >&2
  echo "demo: this checkout has the foundation only: run tools/test.sh for its tests." >&2
  exit 1
fi
exec "$root/tools/launch.sh" --demo both "$@"
