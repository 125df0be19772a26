#!/usr/bin/env bash
# Runs a command so that its LCM multicast traffic can reach nothing else:
#   * in a network namespace of its own (loopback up with the MULTICAST flag,
#     which the official SSL programs look for, and multicast routed to lo)
#     when this user may create one (root, or unprivileged user namespaces);
#   * otherwise on a UDP port of its own, derived from the test name.
# Either way LCM_DEFAULT_URL is set with ttl=0, so nothing leaves the host.
# Inside the namespace the only interface is lo, so the SSL bridge's default
# (the interface the kernel routes the group to, and lo) is lo alone.
# Usage: run_isolated.sh TEST_NAME COMMAND [ARGS...]
set -euo pipefail
name=$1
shift
port=$((20000 + $(printf '%s' "$name" | cksum | cut -d' ' -f1) % 20000))
export LCM_DEFAULT_URL="udpm://239.255.76.67:${port}?ttl=0"

namespace_ok() {
  command -v unshare >/dev/null && command -v ip >/dev/null || return 1
  unshare -n true 2>/dev/null && return 0
  unshare -rn true 2>/dev/null && return 0
  return 1
}

if [ "${UBERSIM_NO_NETNS:-0}" != 1 ] && namespace_ok; then
  flag=-n
  unshare -n true 2>/dev/null || flag=-rn
  exec unshare "$flag" bash -c '
    ip link set lo up multicast on
    ip route add 224.0.0.0/4 dev lo
    exec "$@"' isolated "$@"
fi
# No namespace: stay on our own port. Multicast needs some route; the
# default route serves, and ttl=0 keeps packets on this host. The SSL bridge
# would send on the default interface: UBERSIM_SSL_LOCAL_ONLY keeps it on lo
# with TTL 0 (as its --local-only).
export UBERSIM_SSL_LOCAL_ONLY=1
exec "$@"
