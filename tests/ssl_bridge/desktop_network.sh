#!/usr/bin/env bash
# Runs a command in a network shaped like a team's desktop PC, made for it
# alone, so that SSL multicast on an interface other than lo never touches
# this machine's own network:
#   * a network namespace of its own (the "desktop"): lo up WITHOUT the
#     MULTICAST flag (as on a desktop), and an ethernet-like interface eth0
#     (one end of a veth pair, 198.51.100.10/24, a documentation address) that
#     carries the default route;
#   * a second namespace (the "other PC" on the same network) holding the
#     veth pair's other end, 198.51.100.20/24, with its own default route there.
# The command runs in the desktop namespace with LCM_DEFAULT_URL on ttl=0 and
# UBERSIM_PEER_NETNS naming the other PC's namespace (for nsenter --net=;
# UBERSIM_NSENTER is nsenter's path).
# Without the rights to make namespaces or a veth pair it exits 77 (skipped),
# saying why.
# Usage: desktop_network.sh COMMAND [ARGS...]
set -euo pipefail

skip() {
  echo "SKIPPED: $*"
  exit 77
}

command -v unshare >/dev/null || skip "unshare (util-linux) is not installed"
command -v ip >/dev/null || skip "ip (iproute2) is not installed"
command -v nsenter >/dev/null || skip "nsenter (util-linux) is not installed"
flag=-n
if ! unshare -n true 2>/dev/null; then
  unshare -rn true 2>/dev/null || skip "cannot make a network namespace (not root, no user namespaces)"
  flag=-rn
fi

exec unshare "$flag" bash -c '
set -euo pipefail
if ! error=$(ip link add eth0 type veth peer name peer0 2>&1); then
  echo "SKIPPED: cannot make a veth pair: $error"
  exit 77
fi
ip link set lo up
ip link set lo multicast off
ip addr add 198.51.100.10/24 dev eth0
ip link set eth0 up
ip route add default via 198.51.100.1 dev eth0

# The other PC: a namespace of its own, held by a sleeping process.
unshare -n sleep 100000 &
peer=$!
for _ in $(seq 100); do
  [ "$(readlink /proc/$peer/ns/net)" != "$(readlink /proc/$$/ns/net)" ] && break
  sleep 0.01
done
ip link set peer0 netns "$peer"
nsenter --net=/proc/$peer/ns/net sh -c "
  ip link set lo up
  ip addr add 198.51.100.20/24 dev peer0
  ip link set peer0 up
  ip route add default via 198.51.100.1 dev peer0"

export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0"
export UBERSIM_PEER_NETNS=/proc/$peer/ns/net
UBERSIM_NSENTER=$(command -v nsenter)
export UBERSIM_NSENTER
status=0
"$@" || status=$?
kill "$peer"
exit "$status"' desktop "$@"
