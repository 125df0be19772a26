#!/usr/bin/env bash
# Sets up real teams' software, fetched as git repositories, so that ubersim's interop tests and a
# user can run it against ubersim (docs/real_programs.md):
#   * project-neon/NeonFC-SSL (+ project-neon/NeonPathPlanning): Python, grSim's protocol;
#   * First-Order-RoboCup-SSL/Utama-Core (+ splintered-reality/py_trees, its behaviour-tree
#     library): Python, the SSL simulation protocol;
#   * RoboCup-SSL/grSim's clients/qt: grSim's Qt sample client (sends grSim_Packet on UDP 20011).
# With Debian 12's packages only (no PyPI): Debian's /usr/bin/python3 (3.11) and python3-*
# packages, Qt 5 and protobuf from Debian. Nothing of theirs is changed but config values: ports
# and addresses (every simulator address 127.0.0.1); what is changed is printed.
#
# Usage: setup_real_programs.sh SRC_ROOT OUT_DIR
#   SRC_ROOT holds one folder per repository, <owner>+<name>, each a checkout or a bare git
#   repository (itself or as <owner>+<name>/repo). OUT_DIR receives the programs and, in
#   OUT_DIR/bin, the three programs the tests name:
#     UBERSIM_NEONFC=OUT_DIR/bin/neonfc            (NeonFC-SSL's main; -p CONFIG as upstream)
#     UBERSIM_UTAMA=OUT_DIR/bin/utama-python       (Debian's python3 that imports utama_core)
#     UBERSIM_GRSIM_QT_CLIENT=OUT_DIR/bin/grsim-qt-client
#   and NeonFC configs for both colours in OUT_DIR/neonfc/config_{yellow,blue}.toml.
# Installs Debian packages with apt-get (needs root) unless UBERSIM_NO_APT=1.
set -euo pipefail
if [ $# -ne 2 ]; then
  echo "usage: $0 SRC_ROOT OUT_DIR" >&2
  exit 2
fi
src=$(cd "$1" && pwd)
out=$(mkdir -p "$2" && cd "$2" && pwd)
mkdir -p "$out/bin"

if [ "${UBERSIM_NO_APT:-0}" != 1 ]; then
  apt-get install -y -qq python3-protobuf python3-numpy python3-scipy python3-matplotlib \
    python3-tqdm python3-serial python3-toml python3-pip python3-rich python3-pandas \
    python3-pygame python3-pydot python3-cloudpickle python3-typing-extensions \
    qtbase5-dev libprotobuf-dev protobuf-compiler cmake g++ make xvfb xdotool xauth \
    bsdutils >/dev/null
fi

# unpack OWNER+NAME TARGET: the repository's HEAD (or a checkout's files) into TARGET.
unpack() {
  local from=$src/$1 to=$2
  rm -rf "$to"
  mkdir -p "$to"
  if [ -d "$from/repo" ]; then from=$from/repo; fi
  if [ ! -d "$from" ]; then
    echo "setup_real_programs: $from not found (fetch $1 first)" >&2
    exit 1
  fi
  if [ ! -e "$from/.git" ] && git --git-dir="$from" rev-parse HEAD >/dev/null 2>&1; then
    git --git-dir="$from" archive HEAD | tar -x -C "$to"
    echo "$1 $(git --git-dir="$from" rev-parse HEAD)"
  else
    cp -a "$from/." "$to"
    echo "$1 (copied checkout $(git -C "$from" rev-parse HEAD 2>/dev/null || echo '?'))"
  fi
}

# set_value FILE SECTION KEY VALUE: KEY's value in [SECTION] of a TOML file, said on stdout.
set_value() {
  python3 - "$@" <<'PY'
import re, sys
path, section, key, value = sys.argv[1:5]
text = open(path, encoding="utf-8").read()
start = text.index(f"[{section}]")
end = text.find("\n[", start + 1)
end = len(text) if end < 0 else end
block, n = re.subn(rf"(?m)^{re.escape(key)}\s*=.*$", f"{key} = {value}", text[start:end])
if n != 1:
    sys.exit(f"{path}: [{section}] {key} not found once")
open(path, "w", encoding="utf-8").write(text[:start] + block + text[end:])
print(f"  {path}: [{section}] {key} = {value}")
PY
}

echo "== sources"
unpack project-neon+NeonFC-SSL "$out/neonfc/NeonFC-SSL"
unpack project-neon+NeonPathPlanning "$out/neonfc/NeonPathPlanning"
unpack First-Order-RoboCup-SSL+Utama-Core "$out/utama/Utama-Core"
mkdir -p "$out/utama/pylib"
unpack splintered-reality+py_trees "$out/utama/py_trees-src"
ln -sfn ../py_trees-src/py_trees "$out/utama/pylib/py_trees"
unpack RoboCup-SSL+grSim "$out/grsim/grSim"

echo "== NeonFC-SSL: one config per colour (ports and addresses only)"
# ubersim's SSL bridge: SSL-Vision (geometry) on 10020, tracked frames on 10010 (NeonFC reads
# its robots and ball from them with use_ref_vision = true), referee on 10003, grSim commands
# on 127.0.0.1:20011. Game.input_port/output_port are NeonFC's own sockets: one pair per process.
for colour in yellow blue; do
  config=$out/neonfc/config_$colour.toml
  cp "$out/neonfc/NeonFC-SSL/config.toml" "$config"
  set_value "$config" Game host '"127.0.0.1"'
  # "side" is NeonFC's own goal: ubersim's referee has yellow defend the negative half (left).
  if [ $colour = yellow ]; then ports=(43211 43210 left); else ports=(43221 43220 right); fi
  set_value "$config" Game input_port "${ports[0]}"
  set_value "$config" Game output_port "${ports[1]}"
  set_value "$config" InputLayer vision_port 10020
  set_value "$config" InputLayer autoref_port 10010
  set_value "$config" InputLayer game_controller_port 10003
  set_value "$config" InputLayer side "\"${ports[2]}\""
  set_value "$config" Tracking color "\"$colour\""
  set_value "$config" OutputLayer host_ip '"127.0.0.1"'
  set_value "$config" OutputLayer command_port 20011
done
# NeonFC prints a banner as wide as its terminal (os.get_terminal_size: it fails without one), and
# logs into ./logs (which it does not create): the wrapper gives it a pseudo-terminal (script(1))
# and runs it in the current folder, which must hold logs/.
cat >"$out/bin/neonfc" <<SH
#!/usr/bin/env bash
# NeonFC-SSL's main with Debian's python3; arguments as upstream's (-p CONFIG). Logs go to ./logs.
mkdir -p logs
export PYTHONPATH="$out/neonfc/NeonFC-SSL:$out/neonfc/NeonPathPlanning\${PYTHONPATH:+:\$PYTHONPATH}"
args=\$(printf ' %q' /usr/bin/python3 -u -m neonfc_ssl.main "\$@")
SHELL=/bin/bash exec script -qefc "exec\$args" /dev/null
SH
chmod +x "$out/bin/neonfc"

echo "== Utama-Core: SSL-Vision on ubersim's port"
settings=$out/utama/Utama-Core/utama_core/config/settings.py
sed -i 's/^VISION_PORT = 10006$/VISION_PORT = 10020/' "$settings"
if ! grep -q '^VISION_PORT = 10020$' "$settings"; then
  echo "$settings: VISION_PORT not set" >&2
  exit 1
fi
echo "  $settings: VISION_PORT = 10020"
# Utama-Core asks for numpy 2 and calls numpy.atan2, numpy 2's name for arctan2; Debian 12's
# numpy 1.24 has only arctan2. A sitecustomize beside py_trees (outside Utama-Core's tree) adds
# the name; nothing else of numpy 2 is used.
cat >"$out/utama/pylib/sitecustomize.py" <<'PY'
"""Utama-Core on Debian 12's numpy 1.24: numpy 2's atan2 is numpy 1's arctan2."""
import numpy

if not hasattr(numpy, "atan2"):
    numpy.atan2 = numpy.arctan2
PY
cat >"$out/bin/utama-python" <<SH
#!/usr/bin/env bash
# Debian's python3 with Utama-Core, py_trees and the numpy name shim importable (PyPI's lenses
# and gymnasium are not needed in its grsim mode).
export PYTHONPATH="$out/utama/Utama-Core:$out/utama/pylib\${PYTHONPATH:+:\$PYTHONPATH}"
exec /usr/bin/python3 -u "\$@"
SH
chmod +x "$out/bin/utama-python"
"$out/bin/utama-python" -c "import utama_core.run" >/dev/null

echo "== grSim's Qt client (Debian's Qt 5 and protobuf)"
# grSim's own CMake would build protobuf 3.6.1 from the network when Debian's is 3.21 or newer;
# a project around clients/qt that finds protobuf first builds the client with Debian's.
mkdir -p "$out/grsim/project"
cat >"$out/grsim/project/CMakeLists.txt" <<CM
cmake_minimum_required(VERSION 3.16)
project(grsim_qt_client CXX)
find_package(Protobuf REQUIRED)
add_subdirectory("$out/grsim/grSim/clients/qt" client)
CM
# grSim's CMake and sources warn (cmake_minimum_required 2.8, protobuf's ByteSize): kept in a log.
if ! { cmake -S "$out/grsim/project" -B "$out/grsim/build" -DCMAKE_BUILD_TYPE=Release &&
  cmake --build "$out/grsim/build" -j "$(nproc)"; } >"$out/grsim/build.log" 2>&1; then
  tail -n 30 "$out/grsim/build.log" >&2
  echo "setup_real_programs: grSim's Qt client did not build (log: $out/grsim/build.log)" >&2
  exit 1
fi
ln -sfn "$out/grsim/build/client/client" "$out/bin/grsim-qt-client"

echo "== done: set for the tests (ctest -L interop)"
echo "export UBERSIM_NEONFC=$out/bin/neonfc UBERSIM_NEONFC_CONFIGS=$out/neonfc" \
  "UBERSIM_UTAMA=$out/bin/utama-python UBERSIM_GRSIM_QT_CLIENT=$out/bin/grsim-qt-client"
