#!/usr/bin/env bash
# Starts lcm-spy with the ubersim message types on its class path, so every
# ubersim channel is decoded. (Debian's /usr/bin/lcm-spy passes -Xincgc, which
# Java 17 rejects; this starts the same program directly.)
# Usage: tools/lcm-spy.sh [-l LCM_URL]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
jar=${UBERSIM_BUILD_DIR:-$root/build}/lcmtypes/ubersim_types.jar
[ -f "$jar" ] || { echo "lcm-spy.sh: $jar not found: run tools/build.sh first" >&2; exit 1; }
exec java -Xmx256m -cp "$jar:/usr/share/java/lcm.jar:/usr/share/java/jchart2d.jar" lcm.spy.Spy "$@"
