#!/usr/bin/env bash
# tools/launch.sh --ssl, the one command for an SSL team (docs/ssl_compatibility.md):
#   1. it starts physics, both emulators, the referee, the SSL bridge and the
#      viewer, and prints every port a team needs in one block; the command
#      ports are bound on 127.0.0.1, SSL-Vision and Referee packets arrive on
#      their multicast groups, the viewer answers;
#   2. a second bridge on the same ports exits 1 with one line ("UDP
#      127.0.0.1:10300 is already in use ..."), the first keeps running;
#   3. a second launch.sh --ssl (on another LCM port) exits 1 before it starts
#      anything, naming the program that holds the port;
#   4. SIGTERM stops the set (143) and leaves no process behind;
#   5. --lan --vision-port 10006: the command ports bound on 0.0.0.0, SSL-Vision
#      on 10006, and the block says both.
# Usage: test_launch_ssl.sh SOURCE_DIR  (UBERSIM_BUILD_DIR: the build; run isolated)
set -uo pipefail
source_dir=$1
bin=${UBERSIM_BUILD_DIR:-$source_dir/build}/bin
launch=$source_dir/tools/launch.sh
work=$(mktemp -d "${TMPDIR:-/tmp}/launch-ssl-XXXXXX")
url=${LCM_DEFAULT_URL:?run through tests/run_isolated.sh}
port=${url#*://*:}
port=${port%%\?*}
other_url=${url/:$port/:$((port + 1))}
marker="launchssl$$"
# shellcheck source=../support/script_checks.sh
source "$source_dir/tests/support/script_checks.sh"
launcher=""
cleanup() {
  [ -z "$launcher" ] || kill -TERM "$launcher" 2>/dev/null
  sleep 3
  local pid
  for pid in $(processes_of_this_test); do kill -KILL "$pid" 2>/dev/null; done
}
trap cleanup EXIT
# The bridge's SSL multicast may leave on the default interface: only where lo is the only one
# (the namespace tests/run_isolated.sh makes), never on this machine's own interfaces.
interfaces=$(ip -o link show 2>/dev/null | awk -F': ' '{ sub(/@.*/, "", $2); print $2 }' | tr '\n' ' ')
if [ "$interfaces" != "lo " ]; then
  echo "test_launch_ssl: skipped: interfaces other than lo here (${interfaces:-ip not installed});" \
    "it runs only in a network namespace of its own (tests/run_isolated.sh makes one where it may)"
  exit 77
fi
command -v ss >/dev/null || { echo "test_launch_ssl: ss (iproute2) is not installed"; exit 1; }
command -v python3 >/dev/null || { echo "test_launch_ssl: python3 is not installed"; exit 1; }

# multicast_datagrams GROUP PORT: how many datagrams a socket that joins GROUP
# on 0.0.0.0 (as most team software does) receives on PORT within 3 s.
multicast_datagrams() {
  python3 - "$1" "$2" <<'PY'
import socket, struct, sys, time
group, port = sys.argv[1], int(sys.argv[2])
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
s.bind(("", port))
s.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP, struct.pack("4s4s", socket.inet_aton(group), socket.inet_aton("0.0.0.0")))
s.settimeout(0.2)
count, end = 0, time.time() + 3
while time.time() < end:
    try:
        s.recv(65536)
        count += 1
    except socket.timeout:
        pass
print(count)
PY
}

# 1. The one command.
"$launch" --ssl --channel-prefix "$marker" --log-dir "$work/logs" >"$work/launch.out" 2>"$work/launch.err" </dev/null &
launcher=$!
for _ in $(seq 300); do grep -q "Ctrl-C stops everything" "$work/launch.out" && break; sleep 0.1; done
cat "$work/launch.out" "$work/launch.err"
grep -q "Ctrl-C stops everything" "$work/launch.out" || fail "launch.sh --ssl did not finish starting within 30 s"
for name in physics vision radio referee ssl_bridge viewer; do
  grep -qE "^  $name +pid [0-9]+" "$work/launch.out" || fail "launch.sh --ssl did not start $name"
done
block=$(sed -n "/^ports for your team's software/,/command ports listen/p" "$work/launch.out")
[ -n "$block" ] || fail "no ports block"
for line in "vision +224\.5\.23\.2:10020 .*--vision-port 10006" "tracked +224\.5\.23\.2:10010" \
  "referee +224\.5\.23\.1:10003 .*automatic referee" \
  "grSim commands +127\.0\.0\.1:20011 .*30011 \(blue\) / 30012 \(yellow\)" \
  "simulation control +127\.0\.0\.1:10300" "robot control +127\.0\.0\.1:10301 \(blue\) / 127\.0\.0\.1:10302 \(yellow\)" \
  "viewer +http://127\.0\.0\.1:[0-9]+/" "listen on this host only; --lan"; do
  grep -qE -- "$line" <<<"$block" || fail "the ports block has no line matching '$line'"
done
sleep 2  # the bridge binds once it runs; the first frames follow
bound=$(ss -Huln)
for p in 10300 10301 10302; do
  grep -qE "127\.0\.0\.1:$p " <<<"$bound" || fail "nothing bound on 127.0.0.1:$p"
done
# grSim's port, once the bridge speaks grSim's protocol.
if "$bin/ubersim_ssl_bridge" --help 2>/dev/null | grep -q -- --grsim-port; then
  grep -qE "127\.0\.0\.1:20011 " <<<"$bound" || fail "nothing bound on 127.0.0.1:20011"
fi
vision=$(multicast_datagrams 224.5.23.2 10020)
referee=$(multicast_datagrams 224.5.23.1 10003)
echo "in 3 s on 0.0.0.0: $vision SSL-Vision datagrams, $referee Referee datagrams"
[ "${vision:-0}" -gt 0 ] || fail "no SSL-Vision datagram on 224.5.23.2:10020"
[ "${referee:-0}" -gt 0 ] || fail "no Referee datagram on 224.5.23.1:10003"
viewer_port=$(grep -oE "viewer +http://127\.0\.0\.1:[0-9]+" <<<"$block" | grep -oE "[0-9]+$")
(exec 3<>"/dev/tcp/127.0.0.1/${viewer_port:-1}") 2>/dev/null || fail "the viewer does not answer on ${viewer_port:-?}"

# 2. A second bridge on the same ports (on another LCM port: its own bus).
timeout 20 "$bin/ubersim_ssl_bridge" --lcm-url "$other_url" --channel-prefix "$marker" >"$work/bridge2.out" 2>"$work/bridge2.err"
status=$?
echo "a second bridge -> exit $status: $(cat "$work/bridge2.err")"
[ "$status" = 1 ] || fail "second bridge: exit $status, expected 1"
[ "$(wc -l <"$work/bridge2.err")" = 1 ] || fail "second bridge: not one line on stderr"
grep -q "UDP 127.0.0.1:10300 is already in use" "$work/bridge2.err" || fail "second bridge: the line does not name 127.0.0.1:10300"

# 3. A second launch.sh --ssl on another LCM port: refused before anything starts.
timeout 30 "$launch" --ssl --lcm-url "$other_url" --channel-prefix "$marker" --log-dir "$work/logs2" \
  >"$work/launch2.out" 2>"$work/launch2.err" </dev/null
status=$?
echo "a second launch.sh --ssl -> exit $status: $(cat "$work/launch2.err")"
[ "$status" = 1 ] || fail "second launch.sh --ssl: exit $status, expected 1"
[ "$(wc -l <"$work/launch2.err")" = 1 ] || fail "second launch.sh --ssl: not one line on stderr"
grep -qE "^launch: UDP 127\.0\.0\.1:10300 \(simulation control\) is taken by ubersim_ssl_bridge \(pid [0-9]+\)" "$work/launch2.err" ||
  fail "second launch.sh --ssl: the line does not name the bridge holding 10300"
[ -e "$work/logs2" ] && fail "second launch.sh --ssl made its log folder (started?)"
grep -q "exited with status" "$work/launch.err" && fail "the first set lost a process: $(cat "$work/launch.err")"
kill -0 "$launcher" 2>/dev/null || fail "the first launch.sh is gone"

# 4. SIGTERM stops it all.
kill -TERM "$launcher"
wait "$launcher"
status=$?
launcher=""
echo "launch.sh --ssl after SIGTERM -> exit $status"
[ "$status" = 143 ] || fail "launch.sh --ssl: exit $status after SIGTERM, expected 143: $(cat "$work/launch.err")"
sleep 0.5
[ -z "$(processes_of_this_test)" ] || fail "processes left: $(processes_of_this_test)"

# 5. Open to the LAN, vision on ssl-vision's port.
"$launch" --ssl --lan --vision-port 10006 --channel-prefix "$marker" --log-dir "$work/logs3" \
  >"$work/launch3.out" 2>"$work/launch3.err" </dev/null &
launcher=$!
for _ in $(seq 300); do grep -q "Ctrl-C stops everything" "$work/launch3.out" && break; sleep 0.1; done
sleep 2
bound=$(ss -Huln)
for p in 10300 10301 10302; do
  grep -qE "0\.0\.0\.0:$p " <<<"$bound" || fail "--lan: nothing bound on 0.0.0.0:$p"
done
grep -qE "vision +224\.5\.23\.2:10006 \(SSL-Vision multicast\)$" "$work/launch3.out" || fail "--vision-port 10006: not in the ports block"
grep -q "listen on every interface of this PC (--lan)" "$work/launch3.out" || fail "--lan: the block does not say so"
vision=$(multicast_datagrams 224.5.23.2 10006)
echo "--lan --vision-port 10006: $vision SSL-Vision datagrams on 10006 in 3 s"
[ "${vision:-0}" -gt 0 ] || fail "--vision-port 10006: no SSL-Vision datagram there"
kill -TERM "$launcher"
wait "$launcher"
status=$?
launcher=""
[ "$status" = 143 ] || fail "launch.sh --ssl --lan: exit $status after SIGTERM: $(cat "$work/launch3.err")"

finish "$work"
